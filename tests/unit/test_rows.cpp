// The row kernels (eval_rows, eval_grid_rows in kernels/eval.cl, through Evaluator::evaluateRows,
// the float32 path of evaluateArrays and the grids): the device's normalization and row checks
// give the host readers' bits and messages, at every lane width, for partial groups, unaligned
// arrays and several launches, and never write past the caller's result array.
#include <gtest/gtest.h>

#include <cfloat>
#include <cstdint>
#include <cstdlib>
#include <cmath>
#include <cstring>
#include <random>
#include <string>
#include <tuple>
#include <vector>

#include "brdfcl/arrays.hpp"
#include "brdfcl/io.hpp"
#include "support.hpp"

namespace brdfcl::test {
namespace {

// Raw rows as a user holds them: directions of any length from 1e-44 to 1e38, components exactly
// zero, subnormal or of mixed magnitudes, and a few hand-picked extremes first.
std::vector<float> rawRows(std::mt19937_64& rng, std::size_t n) {
  std::vector<float> rows = {FLT_MAX,        FLT_MAX,   FLT_MAX,   1e-45f, 0.0f, 0.0f,  FLT_TRUE_MIN, FLT_TRUE_MIN, 1.0f,
                             1e30f,          1e-30f,    1.0f,      -3e38f, 2e38f, 1e-40f, 0.0f,        0.0f,         -1e-44f,
                             0x1p-75f,       0x1p-75f,  0x1p-75f,  0x1p50f, 1.0f, 0x1p49f};
  std::uniform_real_distribution<double> u(-1.0, 1.0), exponent(-44.0, 38.0);
  while (rows.size() < 3 * n) {
    const double scale = std::pow(10.0, exponent(rng));
    float row[3];
    for (float& x : row) {
      const double r = u(rng);
      // One component in eight is zero, one in eight is scaled down by up to 2^-100.
      const double v = std::fabs(r) < 0.125 ? 0.0 : std::fabs(r) < 0.25 ? r * std::ldexp(1.0, -int(100 * std::fabs(r))) : r;
      x = float(v * scale);
    }
    if (row[0] == 0.0f && row[1] == 0.0f && row[2] == 0.0f) row[2] = FLT_TRUE_MIN;  // a direction, however short
    rows.insert(rows.end(), row, row + 3);
  }
  rows.resize(3 * n);
  return rows;
}

// What the samples readers make of the same rows (normalizeDirection), as unit-vector Samples.
Samples normalizedOnHost(const std::vector<float>& L, const std::vector<float>& V, const std::vector<std::int64_t>& index) {
  Samples s;
  const std::size_t n = L.size() / 3;
  s.L.resize(3 * n);
  s.V.resize(3 * n);
  for (std::size_t i = 0; i < n; ++i) {
    const double l[3] = {L[3 * i], L[3 * i + 1], L[3 * i + 2]}, v[3] = {V[3 * i], V[3 * i + 1], V[3 * i + 2]};
    EXPECT_TRUE(normalizeDirection(l, &s.L[3 * i])) << "row " << i;
    EXPECT_TRUE(normalizeDirection(v, &s.V[3 * i])) << "row " << i;
    s.material.push_back(index.empty() ? 0u : std::uint32_t(index[i]));
  }
  return s;
}

// A file's (N, 7) rows (material, Lx Ly Lz, Vx Vy Vz) of the same directions and indices.
std::vector<float> tableRows(const std::vector<float>& L, const std::vector<float>& V, const std::vector<std::int64_t>& index) {
  std::vector<float> table(7 * index.size());
  for (std::size_t i = 0; i < index.size(); ++i) {
    table[7 * i] = float(index[i]);
    for (int c = 0; c < 3; ++c) table[7 * i + 1 + c] = L[3 * i + c], table[7 * i + 4 + c] = V[3 * i + c];
  }
  return table;
}

ArraySamples arrays(const float* L, const float* V, const std::int64_t* index, std::size_t n) {
  ArraySamples a;
  a.L.data = L;
  a.V.data = V;
  a.material = index;
  a.count = n;
  return a;
}

// Bit for bit, or within maxUlps units in the last place (same sign) where two compilations
// of one formula may contract multiply-adds differently.
void expectSameBits(const float* got, const float* want, std::size_t n, const std::string& what, int maxUlps = 0) {
  for (std::size_t i = 0; i < n; ++i) {
    std::int32_t a, b;
    std::memcpy(&a, &got[i], 4);
    std::memcpy(&b, &want[i], 4);
    const bool same = maxUlps == 0 ? a == b : (a < 0) == (b < 0) && std::abs(std::int64_t(a) - b) <= maxUlps;
    ASSERT_TRUE(same) << what << ": value " << i << " (row " << i / 3 << ") is " << got[i] << ", the other path gives "
                      << want[i] << (maxUlps ? " (allowed: " + std::to_string(maxUlps) + " ulp)" : std::string());
  }
}

std::string errorOf(const std::function<void()>& f) {
  try {
    f();
  } catch (const Error& e) {
    return e.what();
  }
  return "(no error)";
}

class RowsAtWidth : public testing::TestWithParam<int> {};

// Device normalization = host normalization, seen through f: every f of the row kernel equals,
// bit for bit, the SoA kernel's f on the directions the samples readers normalized on the host.
TEST_P(RowsAtWidth, DeviceNormalizationGivesTheReadersBits) {
  ForcedLanes forced(GetParam());
  std::mt19937_64 rng(seed() + 31 + std::uint64_t(GetParam()));
  std::vector<MaterialParams> materials;
  for (int m = 0; m < 5; ++m) materials.push_back(randomMaterial(rng));
  for (std::size_t n : {std::size_t(1), std::size_t(7), std::size_t(16), std::size_t(37), std::size_t(20011)}) {
    const auto L = rawRows(rng, n), V = rawRows(rng, n);
    std::vector<std::int64_t> index(n);
    for (auto& k : index) k = std::int64_t(rng() % materials.size());
    Evaluator ev(runtime(), EvalOptions{});
    const std::vector<float> want = ev.evaluate(materials, normalizedOnHost(L, V, index));
    std::vector<float> got(3 * n);
    evaluateArrays(ev, materials, arrays(L.data(), V.data(), index.data(), n), got.data());
    expectSameBits(got.data(), want.data(), 3 * n, std::to_string(n) + " rows, W = " + std::to_string(GetParam()));
    // One material without an index: the splat path.
    const std::vector<MaterialParams> one = {materials[1]};
    const std::vector<float> wantOne = ev.evaluate(one, normalizedOnHost(L, V, {}));
    evaluateArrays(ev, one, arrays(L.data(), V.data(), nullptr, n), got.data());
    expectSameBits(got.data(), wantOne.data(), 3 * n, std::to_string(n) + " rows, one material");
  }
}

// The grid of rows: material k's block equals evaluateArrays with every index k.
TEST_P(RowsAtWidth, GridBlocksEqualPerSampleEvaluation) {
  ForcedLanes forced(GetParam());
  std::mt19937_64 rng(seed() + 57 + std::uint64_t(GetParam()));
  std::vector<MaterialParams> materials;
  for (int m = 0; m < 4; ++m) materials.push_back(randomMaterial(rng));
  const std::size_t n = 1000 + std::size_t(GetParam());
  const auto L = rawRows(rng, n), V = rawRows(rng, n);
  Evaluator ev(runtime(), EvalOptions{});
  std::vector<float> grid(3 * n * materials.size());
  evaluateGridArrays(ev, materials, arrays(L.data(), V.data(), nullptr, n), grid.data());
  for (std::size_t m = 0; m < materials.size(); ++m) {
    std::vector<std::int64_t> index(n, std::int64_t(m));
    std::vector<float> rows(3 * n);
    evaluateArrays(ev, materials, arrays(L.data(), V.data(), index.data(), n), rows.data());
    expectSameBits(grid.data() + 3 * m * n, rows.data(), 3 * n, "grid block of material " + std::to_string(m));
  }
}

// A samples file's (N, 7) rows (material, L, V) give the bits of the same samples as arrays, and
// their bad rows (a fractional or out-of-range index, a zero direction) are found at their row.
TEST_P(RowsAtWidth, TableRowsGiveTheArraysBits) {
  ForcedLanes forced(GetParam());
  std::mt19937_64 rng(seed() + 71 + std::uint64_t(GetParam()));
  std::vector<MaterialParams> materials;
  for (int m = 0; m < 3; ++m) materials.push_back(randomMaterial(rng));
  Evaluator ev(runtime(), EvalOptions{});
  for (std::size_t n : {std::size_t(1), std::size_t(15), std::size_t(16), std::size_t(45), std::size_t(5003)}) {
    const auto L = rawRows(rng, n), V = rawRows(rng, n);
    std::vector<std::int64_t> index(n);
    for (auto& k : index) k = std::int64_t(rng() % materials.size());
    const std::vector<float> table = tableRows(L, V, index);
    std::vector<float> want(3 * n), got(3 * n);
    evaluateArrays(ev, materials, arrays(L.data(), V.data(), index.data(), n), want.data());
    ASSERT_EQ(ev.evaluateTableRows(materials, table.data(), n, got.data()), n);
    expectSameBits(got.data(), want.data(), 3 * n, std::to_string(n) + " table rows, W = " + std::to_string(GetParam()));
    if (n < 45) continue;
    for (const auto& [row, column, value] : {std::tuple{n - 1, 0, 1.5f}, std::tuple{n / 2, 0, 3.0f},
                                             std::tuple{std::size_t(17), 0, -0.0f - 1.0f}, std::tuple{std::size_t(3), 4, NAN}}) {
      auto bad = table;
      bad[7 * row + std::size_t(column)] = value;
      EXPECT_EQ(ev.evaluateTableRows(materials, bad.data(), n, got.data()), row) << "column " << column;
      EXPECT_EQ(ev.evaluateTableRows(materials, bad.data(), n, got.data(), 32), row) << "in launches of 32";
    }
    auto zero = table;
    std::fill_n(zero.begin() + 7 * 40 + 1, 3, 0.0f);
    EXPECT_EQ(ev.evaluateTableRows(materials, zero.data(), n, got.data()), 40u);
  }
}

// The planes kernel (eval_samples, SoaBatch: the bench's and the peers' path) gives the bits of
// the row kernel that every library path uses, many materials gathered or one read once.
TEST_P(RowsAtWidth, PlanesKernelGivesTheRowKernelsBits) {
  ForcedLanes forced(GetParam());
  std::mt19937_64 rng(seed() + 83 + std::uint64_t(GetParam()));
  for (std::size_t count : {std::size_t(1), std::size_t(7)}) {
    std::vector<MaterialParams> materials;
    for (std::size_t m = 0; m < count; ++m) materials.push_back(randomMaterial(rng));
    const Samples s = randomSamples(rng, 3001, count);
    Evaluator ev(runtime(), EvalOptions{});
    const std::vector<float> rows = ev.evaluate(materials, s);
    SoaBatch batch(ev, materials, s.size());
    for (int c = 0; c < 3; ++c)
      for (std::size_t i = 0; i < s.size(); ++i) {
        batch.direction(c)[i] = s.L[3 * i + std::size_t(c)];
        batch.direction(3 + c)[i] = s.V[3 * i + std::size_t(c)];
      }
    std::copy(s.material.begin(), s.material.end(), batch.materialIndex());
    batch.setCount(s.size());
    batch.run();
    std::vector<float> planes(3 * s.size());
    for (std::size_t i = 0; i < s.size(); ++i)
      for (int c = 0; c < 3; ++c) planes[3 * i + std::size_t(c)] = batch.result(c)[i];
    // PoCL compiles both kernels' BRDF alike; NVIDIA's compiler, at widths forced past its W = 1,
    // contracts a multiply-add differently between the two (1 ulp seen on an H200 at W = 8).
    const int ulps = runtime().info().type == "CPU" ? 0 : 4;
    expectSameBits(planes.data(), rows.data(), planes.size(), std::to_string(count) + " materials, planes kernel", ulps);
  }
}

INSTANTIATE_TEST_SUITE_P(Widths, RowsAtWidth, testing::Values(0, 1, 4, 8),
                         [](const testing::TestParamInfo<int>& i) { return i.param ? "W" + std::to_string(i.param) : std::string("Default"); });

// Arrays at any float alignment (numpy slices), in launches of a few rows: the same bits as one
// aligned launch, and nothing written outside the result rows.
TEST(Rows, UnalignedArraysAndSmallLaunchesGiveTheSameBits) {
  std::mt19937_64 rng(seed() + 91);
  std::vector<MaterialParams> materials = {randomMaterial(rng), randomMaterial(rng)};
  const std::size_t n = 333;
  const auto L = rawRows(rng, n), V = rawRows(rng, n);
  std::vector<std::int64_t> index(n);
  for (auto& k : index) k = std::int64_t(rng() % 2);
  Evaluator ev(runtime(), EvalOptions{});
  std::vector<float> want(3 * n);
  evaluateArrays(ev, materials, arrays(L.data(), V.data(), index.data(), n), want.data());
  for (std::size_t shift : {1, 2, 3, 5}) {
    std::vector<float> l(3 * n + shift), v(3 * n + 2 * shift), out(3 * n + 2 * shift + 8, -7.0f);
    std::copy(L.begin(), L.end(), l.begin() + std::ptrdiff_t(shift));
    std::copy(V.begin(), V.end(), v.begin() + std::ptrdiff_t(2 * shift));
    for (std::size_t launch : {std::size_t(0), std::size_t(16), std::size_t(48), std::size_t(100)}) {
      std::fill(out.begin(), out.end(), -7.0f);
      evaluateArrays(ev, materials, arrays(l.data() + shift, v.data() + 2 * shift, index.data(), n),
                     out.data() + shift, launch);
      const std::string what = "shift " + std::to_string(shift) + ", launches of " + std::to_string(launch);
      expectSameBits(out.data() + shift, want.data(), 3 * n, what);
      for (std::size_t i = 0; i < shift; ++i) ASSERT_EQ(out[i], -7.0f) << what << ": written before the rows";
      for (std::size_t i = shift + 3 * n; i < out.size(); ++i) ASSERT_EQ(out[i], -7.0f) << what << ": written past the rows";
    }
  }
}

// A bad row anywhere (first group, a middle launch, the partial last group) is found, the lowest
// wins, and the words are those of the float64 path, which checks every row on the host.
TEST(Rows, TheLowestBadRowIsWordedAsTheHostWordsIt) {
  std::mt19937_64 rng(seed() + 101);
  const std::vector<MaterialParams> materials = {randomMaterial(rng), randomMaterial(rng), randomMaterial(rng)};
  const std::size_t n = 1000;
  Evaluator ev(runtime(), EvalOptions{});
  struct Case {
    std::size_t row;
    int field;  // 0..5: Lx..Vz set to `value`; 6: the index set to `index`; 7: L zero; 8: V zero
    float value;
    std::int64_t index;
    std::string message;
  };
  const Case cases[] = {
      {0, 0, NAN, 0, "row 0: field 'Lx' is not finite: nan"},
      {17, 5, INFINITY, 0, "row 17: field 'Vz' is not finite: inf"},
      {500, 4, -INFINITY, 0, "row 500: field 'Vy' is not finite: -inf"},
      {999, 7, 0, 0, "row 999: L has zero length"},
      {993, 8, 0, 0, "row 993: V has zero length"},
      {64, 6, 0, 3, "row 64: material index 3 out of range (3 materials)"},
      {65, 6, 0, -1, "row 65: material index -1 is not a non-negative integer"},
      {66, 6, 0, std::int64_t(1) << 32, "row 66: material index 4294967296 out of range (3 materials)"},
  };
  for (std::size_t launch : {std::size_t(0), std::size_t(96)}) {
    for (const auto& c : cases) {
      std::vector<float> L(3 * n, 0.5f), V(3 * n, 0.5f), out(3 * n);
      std::vector<std::int64_t> index(n, 1);
      if (c.field < 3) L[3 * c.row + c.field] = c.value;
      if (c.field >= 3 && c.field < 6) V[3 * c.row + c.field - 3] = c.value;
      if (c.field == 6) index[c.row] = c.index;
      if (c.field == 7) std::fill_n(L.begin() + std::ptrdiff_t(3 * c.row), 3, 0.0f);
      if (c.field == 8) std::fill_n(V.begin() + std::ptrdiff_t(3 * c.row), 3, 0.0f);
      // A later bad row must not win over this one.
      if (c.row + 7 < n) L[3 * (c.row + 7)] = NAN;
      const std::vector<double> L64(L.begin(), L.end()), V64(V.begin(), V.end());
      ArraySamples wide = arrays(nullptr, nullptr, index.data(), n);
      wide.L = {L64.data(), DirectionArray::Type::Float64};
      wide.V = {V64.data(), DirectionArray::Type::Float64};
      const std::string got =
          errorOf([&] { evaluateArrays(ev, materials, arrays(L.data(), V.data(), index.data(), n), out.data(), launch); });
      EXPECT_EQ(got, c.message) << "launches of " << launch;
      EXPECT_EQ(errorOf([&] { evaluateArrays(ev, materials, wide, out.data(), launch); }), c.message);
      const std::size_t bad = ev.evaluateRows(materials, {L.data(), V.data(), index.data(), n, launch}, out.data(), true);
      EXPECT_EQ(bad, c.row) << c.message;
    }
  }
}

// Unit-vector samples (evaluateGrid): only NaN and infinities are caught, on the device, and worded
// as evaluate() words them.
TEST(Rows, GridOfSamplesWordsANonFiniteDirection) {
  std::mt19937_64 rng(seed() + 113);
  const std::vector<MaterialParams> materials = {randomMaterial(rng), randomMaterial(rng)};
  Samples s = randomSamples(rng, 300, 2);
  Evaluator ev(runtime(), EvalOptions{});
  s.V[3 * 211 + 2] = INFINITY;
  s.L[3 * 250] = NAN;
  EXPECT_EQ(errorOf([&] { ev.evaluateGrid(materials, s); }), "sample 211: Vz is not finite: inf");
  EXPECT_EQ(errorOf([&] { ev.evaluate(materials, s); }), "sample 211: Vz is not finite: inf");
}

// The common case beside the extremes: whole groups of directions of ordinary length (the raw rows
// above span 1e-44 to 1e38, so nearly every group there holds an extreme row) give the readers'
// bits through the table rows (eval_table_rows) and the (N, 3) rows (eval_rows).

// Directions as renderers and scanners hand them over: lengths from 2^-30 to 2^30, no component
// small beside the others, in whole groups of 16. Every 997th row has one component of 2^-60 of
// its length and every 89th a signed zero, so that some groups mix ordinary and extreme rows.
std::vector<float> ordinaryRows(std::mt19937_64& rng, std::size_t n) {
  std::uniform_real_distribution<double> u(-1.0, 1.0), exponent(-30.0, 30.0);
  std::vector<float> rows(3 * n);
  for (std::size_t i = 0; i < n; ++i) {
    const double scale = std::exp2(exponent(rng));
    for (int c = 0; c < 3; ++c) {
      double r = u(rng);
      if (std::fabs(r) < 0.01) r = 0.5;
      rows[3 * i + std::size_t(c)] = float(r * scale);
    }
    if (i % 997 == 5) rows[3 * i + i % 3] = float(std::ldexp(rows[3 * i + (i + 1) % 3], -60));
    if (i % 89 == 3) rows[3 * i + (i + 2) % 3] = (i & 1) ? -0.0f : 0.0f;
  }
  return rows;
}

class TableRowsAtWidth : public testing::TestWithParam<int> {};

TEST_P(TableRowsAtWidth, OrdinaryDirectionsGiveTheReadersBits) {
  ForcedLanes forced(GetParam());
  std::mt19937_64 rng(seed() + 113 + std::uint64_t(GetParam()));
  std::vector<MaterialParams> materials;
  for (int m = 0; m < 4; ++m) materials.push_back(randomMaterial(rng));
  Evaluator ev(runtime(), EvalOptions{});
  for (std::size_t n : {std::size_t(16), std::size_t(40009)}) {
    const auto L = ordinaryRows(rng, n), V = ordinaryRows(rng, n);
    std::vector<std::int64_t> index(n);
    for (auto& k : index) k = std::int64_t(rng() % materials.size());
    const std::vector<float> table = tableRows(L, V, index);
    const std::vector<float> want = ev.evaluate(materials, normalizedOnHost(L, V, index));
    std::vector<float> got(3 * n);
    ASSERT_EQ(ev.evaluateTableRows(materials, table.data(), n, got.data()), n);
    expectSameBits(got.data(), want.data(), 3 * n, std::to_string(n) + " ordinary table rows, W = " + std::to_string(GetParam()));
    evaluateArrays(ev, materials, arrays(L.data(), V.data(), index.data(), n), got.data());
    expectSameBits(got.data(), want.data(), 3 * n, std::to_string(n) + " ordinary (N, 3) rows, W = " + std::to_string(GetParam()));
  }
}

INSTANTIATE_TEST_SUITE_P(Widths, TableRowsAtWidth, testing::Values(0, 1, 4, 8),
                         [](const testing::TestParamInfo<int>& i) { return i.param ? "W" + std::to_string(i.param) : std::string("Default"); });

}  // namespace
}  // namespace brdfcl::test
