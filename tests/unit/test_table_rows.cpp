// The row kernels' normalization on directions of ordinary length, whole groups of them: the table
// rows (eval_table_rows) and the (N, 3) rows (eval_rows) give the host readers' bits. test_rows.cpp's
// raw rows span 1e-44 to 1e38, so nearly every group there holds an extreme row; this pins the common case.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <cstring>
#include <random>
#include <string>
#include <vector>

#include "brdfcl/arrays.hpp"
#include "brdfcl/io.hpp"
#include "support.hpp"

namespace brdfcl::test {
namespace {

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

Samples normalizedOnHost(const std::vector<float>& L, const std::vector<float>& V, const std::vector<std::int64_t>& index) {
  Samples s;
  const std::size_t n = L.size() / 3;
  s.L.resize(3 * n);
  s.V.resize(3 * n);
  for (std::size_t i = 0; i < n; ++i) {
    const double l[3] = {L[3 * i], L[3 * i + 1], L[3 * i + 2]}, v[3] = {V[3 * i], V[3 * i + 1], V[3 * i + 2]};
    EXPECT_TRUE(normalizeDirection(l, &s.L[3 * i])) << "row " << i;
    EXPECT_TRUE(normalizeDirection(v, &s.V[3 * i])) << "row " << i;
    s.material.push_back(std::uint32_t(index[i]));
  }
  return s;
}

void expectSameBits(const std::vector<float>& got, const std::vector<float>& want, const std::string& what) {
  ASSERT_EQ(got.size(), want.size());
  for (std::size_t i = 0; i < got.size(); ++i)
    ASSERT_EQ(0, std::memcmp(&got[i], &want[i], 4))
        << what << ": value " << i << " (row " << i / 3 << ") is " << got[i] << ", the readers' rows give " << want[i];
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
    std::vector<float> table(7 * n);
    for (std::size_t i = 0; i < n; ++i) {
      index[i] = std::int64_t(rng() % materials.size());
      table[7 * i] = float(index[i]);
      for (int c = 0; c < 3; ++c) table[7 * i + 1 + c] = L[3 * i + c], table[7 * i + 4 + c] = V[3 * i + c];
    }
    const std::vector<float> want = ev.evaluate(materials, normalizedOnHost(L, V, index));
    std::vector<float> got(3 * n);
    ASSERT_EQ(ev.evaluateTableRows(materials, table.data(), n, got.data()), n);
    expectSameBits(got, want, std::to_string(n) + " table rows, W = " + std::to_string(GetParam()));
    ArraySamples a;
    a.L.data = L.data();
    a.V.data = V.data();
    a.material = index.data();
    a.count = n;
    evaluateArrays(ev, materials, a, got.data());
    expectSameBits(got, want, std::to_string(n) + " (N, 3) rows, W = " + std::to_string(GetParam()));
  }
}

INSTANTIATE_TEST_SUITE_P(Widths, TableRowsAtWidth, testing::Values(0, 1, 4, 8),
                         [](const testing::TestParamInfo<int>& i) { return i.param ? "W" + std::to_string(i.param) : std::string("Default"); });

}  // namespace
}  // namespace brdfcl::test
