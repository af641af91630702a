// The row paths through pinned, double-buffered staging (eval/staging.hpp, forced on the CPU
// device with BRDFCL_STAGING=1) give the in-place path's bytes and bad rows at every chunk
// boundary, and rows kept in device memory (DeviceArray) give evaluate()'s bytes and messages.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <limits>
#include <random>
#include <string>
#include <vector>

#include "brdfcl/device_array.hpp"
#include "support.hpp"

namespace brdfcl::test {
namespace {

// BRDFCL_STAGING for the object's lifetime (the row paths read it on every call).
class ForcedStaging {
 public:
  explicit ForcedStaging(const char* value) {
    if (const char* e = std::getenv("BRDFCL_STAGING")) saved_ = e, had_ = true;
    ::setenv("BRDFCL_STAGING", value, 1);
  }
  ~ForcedStaging() { had_ ? ::setenv("BRDFCL_STAGING", saved_.c_str(), 1) : ::unsetenv("BRDFCL_STAGING"); }
  ForcedStaging(const ForcedStaging&) = delete;
  ForcedStaging& operator=(const ForcedStaging&) = delete;

 private:
  std::string saved_;
  bool had_ = false;
};

std::vector<MaterialParams> materials(std::size_t n) {
  std::mt19937_64 rng(seed() + 27);
  std::vector<MaterialParams> m;
  for (std::size_t i = 0; i < n; ++i) m.push_back(randomMaterial(rng));
  return m;
}

// Rows of any length (the kernels normalize them), a fixed pattern of materials.
struct Rows {
  std::vector<float> L, V;
  std::vector<std::int64_t> index;
  std::vector<std::uint32_t> index32;
};

Rows rows(std::size_t n, std::size_t materialCount) {
  std::mt19937_64 rng(seed() + n);
  std::uniform_real_distribution<float> u(-2.0f, 2.0f);
  Rows r;
  for (std::size_t i = 0; i < 3 * n; ++i) {
    r.L.push_back(u(rng));
    r.V.push_back(u(rng));
  }
  for (std::size_t i = 0; i < n; ++i) {
    r.index.push_back(std::int64_t(i * 7 % materialCount));
    r.index32.push_back(std::uint32_t(i * 7 % materialCount));
  }
  return r;
}

// The result array with a canary after it: no path may write past the rows it was given.
constexpr float kCanary = -12345.0f;

std::vector<float> withCanary(std::size_t floats) {
  std::vector<float> v(floats + 16, std::numeric_limits<float>::quiet_NaN());
  for (std::size_t i = floats; i < v.size(); ++i) v[i] = kCanary;
  return v;
}

void expectSameBytes(const std::vector<float>& staged, const std::vector<float>& inPlace, const std::string& what) {
  ASSERT_EQ(staged.size(), inPlace.size()) << what;
  for (std::size_t i = 0; i < staged.size(); ++i)
    ASSERT_EQ(std::memcmp(&staged[i], &inPlace[i], 4), 0)
        << what << ": float " << i << " is " << staged[i] << " staged, " << inPlace[i] << " in place";
}

// Both paths of one call: `run(rgb)` returns the bad row it reports.
template <class F>
void expectSamePaths(std::size_t floats, const F& run, const std::string& what) {
  std::vector<float> a = withCanary(floats), b = withCanary(floats);
  std::size_t badA, badB;
  {
    ForcedStaging s("1");
    badA = run(a.data());
  }
  {
    ForcedStaging s("0");
    badB = run(b.data());
  }
  EXPECT_EQ(badA, badB) << what;
  expectSameBytes(a, b, what);
  for (std::size_t i = floats; i < a.size(); ++i) ASSERT_EQ(a[i], kCanary) << what << ": written past the rows";
}

TEST(Staging, EvaluateRowsMatchInPlaceAtChunkBoundaries) {
  Evaluator ev(runtime(), EvalOptions{});
  const auto m = materials(3);
  // N = 0 and 1, N a multiple of the launch, one more and one less, and launches not a
  // multiple of the lane width; the largest N runs many launches on both slots.
  for (const std::size_t n : {0, 1, 15, 16, 17, 255, 256, 257, 1000, 4099})
    for (const std::size_t launch : {0, 16, 100, 256})
      for (int indexKind = 0; indexKind < 3; ++indexKind)
        for (const bool normalize : {false, true}) {
          const Rows r = rows(n, m.size());
          Evaluator::Rows in;
          in.L = r.L.data();
          in.V = r.V.data();
          in.count = n;
          in.launch = launch;
          if (indexKind == 1) in.index = r.index.data();
          if (indexKind == 2) in.index32 = r.index32.data();
          // Unnormalized rows are no unit vectors: the in-place path is the reference either way.
          expectSamePaths(3 * n, [&](float* rgb) { return ev.evaluateRows(m, in, rgb, normalize); },
                          "evaluateRows n=" + std::to_string(n) + " launch=" + std::to_string(launch) +
                              " index=" + std::to_string(indexKind) + " normalize=" + std::to_string(normalize));
        }
}

TEST(Staging, BadRowsInLaterChunksAreTheInPlacePathsRows) {
  Evaluator ev(runtime(), EvalOptions{});
  const auto m = materials(2);
  for (const std::size_t badAt : {0, 99, 100, 401, 999}) {
    Rows r = rows(1000, m.size());
    r.V[3 * badAt + 1] = std::numeric_limits<float>::infinity();
    r.index[std::min<std::size_t>(badAt + 250, 999)] = 7;  // a second, later bad row
    Evaluator::Rows in;
    in.L = r.L.data();
    in.V = r.V.data();
    in.index = r.index.data();
    in.count = 1000;
    in.launch = 100;
    std::vector<float> rgb(3000);
    ForcedStaging s("1");
    EXPECT_EQ(ev.evaluateRows(m, in, rgb.data(), true), badAt);
  }
}

TEST(Staging, TableRowsMatchInPlace) {
  Evaluator ev(runtime(), EvalOptions{});
  const auto m = materials(4);
  for (const std::size_t n : {0, 1, 17, 1000})
    for (const std::size_t launch : {0, 96, 100}) {
      const Rows r = rows(n, m.size());
      std::vector<float> table(7 * n);
      for (std::size_t i = 0; i < n; ++i) {
        table[7 * i] = float(r.index[i]);
        for (int k = 0; k < 3; ++k) {
          table[7 * i + 1 + k] = r.L[3 * i + k];
          table[7 * i + 4 + k] = r.V[3 * i + k];
        }
      }
      if (n > 500) table[7 * 501] = 1.5f;  // no integer index: the same bad row either way
      expectSamePaths(3 * n, [&](float* rgb) { return ev.evaluateTableRows(m, table.data(), n, rgb, launch); },
                      "evaluateTableRows n=" + std::to_string(n) + " launch=" + std::to_string(launch));
    }
}

TEST(Staging, GridRowsMatchInPlace) {
  Evaluator ev(runtime(), EvalOptions{});
  const auto m = materials(5);
  // Launches of one material and of several; a sub-block of the materials.
  for (const std::size_t n : {1, 33, 1000})
    for (const std::size_t launch : {0, 64, 100, 4000})
      for (const auto& [first, count] : {std::pair<std::size_t, std::size_t>{0, 5}, {1, 3}}) {
        const Rows r = rows(n, m.size());
        Evaluator::Rows in;
        in.L = r.L.data();
        in.V = r.V.data();
        in.count = n;
        in.launch = launch;
        expectSamePaths(3 * n * count,
                        [&](float* rgb) { return ev.evaluateGridRows(m, in, rgb, true, first, count); },
                        "evaluateGridRows n=" + std::to_string(n) + " launch=" + std::to_string(launch) + " first=" +
                            std::to_string(first));
      }
}

TEST(Staging, SampleAndPdfMatchTheCopyPath) {
  Evaluator ev(runtime(), EvalOptions{});
  const auto m = materials(3);
  for (const std::size_t n : {0, 1, 1000}) {
    std::mt19937_64 rng(seed() + 5);
    const Samples s = randomSamples(rng, n, m.size());
    std::vector<float> u(3 * n);
    Evaluator::drawUniforms(seed(), 0, n, u.data());
    expectSamePaths(7 * n,
                    [&](float* out) {
                      ev.sample(m, s.material.data(), s.V.data(), u.data(), n, out);
                      return std::size_t(0);
                    },
                    "sample n=" + std::to_string(n));
    expectSamePaths(n,
                    [&](float* out) {
                      ev.pdf(m, s, out);
                      return std::size_t(0);
                    },
                    "pdf n=" + std::to_string(n));
  }
}

// The pinned slots are kept between calls and grow: a small call, a large one, a small one again.
TEST(Staging, SlotsReusedAcrossCallsOfEverySize) {
  Evaluator ev(runtime(), EvalOptions{});
  const auto m = materials(2);
  for (const std::size_t n : {10, 300000, 10, 70000}) {
    const Rows r = rows(n, m.size());
    Evaluator::Rows in;
    in.L = r.L.data();
    in.V = r.V.data();
    in.index32 = r.index32.data();
    in.count = n;
    expectSamePaths(3 * n, [&](float* rgb) { return ev.evaluateRows(m, in, rgb, true); }, "n=" + std::to_string(n));
  }
}

TEST(Staging, UnknownSettingIsRefused) {
  Evaluator ev(runtime(), EvalOptions{});
  const Rows r = rows(4, 1);
  Evaluator::Rows in;
  in.L = r.L.data();
  in.V = r.V.data();
  in.count = 4;
  std::vector<float> rgb(12);
  ForcedStaging s("yes");
  EXPECT_EQ(errorOf([&] { ev.evaluateRows(materials(1), in, rgb.data(), true); }),
            "BRDFCL_STAGING=yes is not supported; use 0 or 1");
}

// ---- DeviceArray ----

DeviceArray upload(Runtime& rt, const std::vector<float>& v) {
  DeviceArray a(rt, DeviceArray::Type::Float32, v.size());
  a.upload(v.data(), v.size());
  return a;
}

Samples unitSamples(std::size_t n, std::size_t materialCount) {
  std::mt19937_64 rng(seed() + 11 + n);
  return randomSamples(rng, n, materialCount);
}

TEST(DeviceArrays, EvaluateGivesTheHostPathsBytes) {
  Evaluator ev(runtime(), EvalOptions{});
  const auto m = materials(3);
  for (const std::size_t n : {0, 1, 17, 5000}) {
    const Samples s = unitSamples(n, m.size());
    const std::vector<float> want = ev.evaluate(m, s);
    const DeviceArray L = upload(runtime(), s.L), V = upload(runtime(), s.V);
    DeviceArray index(runtime(), DeviceArray::Type::UInt32, n);
    index.upload(s.material.data(), n);
    DeviceArray rgb(runtime(), DeviceArray::Type::Float32, 3 * n);
    ev.evaluate(m, L, V, &index, rgb);
    std::vector<float> got(3 * n);
    rgb.download(got.data(), got.size());
    expectSameBytes(got, want, "device n=" + std::to_string(n));
  }
}

// Chained work: the results of one call stay on the device as the next call's input (the
// colours, all positive above the horizon, as view directions).
TEST(DeviceArrays, ResultsFeedTheNextCallWithoutTheHost) {
  Evaluator ev(runtime(), EvalOptions{});
  const auto m = materials(1);
  Domain above;
  above.belowHorizon = 0;
  std::mt19937_64 rng(seed() + 3);
  const Samples s = randomSamples(rng, 1000, 1, above);
  const DeviceArray L = upload(runtime(), s.L), V = upload(runtime(), s.V);
  DeviceArray rgb(runtime(), DeviceArray::Type::Float32, 3000), again(runtime(), DeviceArray::Type::Float32, 3000);
  ev.evaluate(m, L, V, nullptr, rgb);
  ev.evaluate(m, L, rgb, nullptr, again, true);

  std::vector<float> first(3000), host(3000), second(3000);
  rgb.download(first.data(), 3000);
  again.download(second.data(), 3000);
  Evaluator::Rows in;
  in.L = s.L.data();
  in.V = first.data();
  in.count = 1000;
  ForcedStaging plain("0");
  ASSERT_EQ(ev.evaluateRows(m, in, host.data(), true), 1000u);
  expectSameBytes(second, host, "chained");
}

TEST(DeviceArrays, RowsWithoutAnIndexUseMaterialZero) {
  Evaluator ev(runtime(), EvalOptions{});
  const auto m = materials(2);
  Samples s = unitSamples(100, 1);
  const std::vector<float> want = ev.evaluate(m, s);
  DeviceArray rgb(runtime(), DeviceArray::Type::Float32, 300);
  ev.evaluate(m, upload(runtime(), s.L), upload(runtime(), s.V), nullptr, rgb);
  std::vector<float> got(300);
  rgb.download(got.data(), 300);
  expectSameBytes(got, want, "no index");
}

TEST(DeviceArrays, ArraysOfAnotherRuntimeAreRefused) {
  Evaluator ev(runtime(), EvalOptions{});
  Runtime other;
  const Samples s = unitSamples(10, 1);
  const DeviceArray L = upload(runtime(), s.L), V = upload(runtime(), s.V), foreignV = upload(other, s.V);
  DeviceArray rgb(runtime(), DeviceArray::Type::Float32, 30), foreignRgb(other, DeviceArray::Type::Float32, 30);
  EXPECT_EQ(errorOf([&] { ev.evaluate(materials(1), L, foreignV, nullptr, rgb); }),
            "device array V belongs to another Runtime; create it on the evaluator's Runtime");
  EXPECT_EQ(errorOf([&] { ev.evaluate(materials(1), L, V, nullptr, foreignRgb); }),
            "device array rgb belongs to another Runtime; create it on the evaluator's Runtime");
}

TEST(DeviceArrays, WrongTypesSizesAndAliasesAreRefused) {
  Evaluator ev(runtime(), EvalOptions{});
  const auto m = materials(2);
  const Samples s = unitSamples(10, 2);
  const DeviceArray L = upload(runtime(), s.L), V = upload(runtime(), s.V);
  DeviceArray rgb(runtime(), DeviceArray::Type::Float32, 30), shortRgb(runtime(), DeviceArray::Type::Float32, 27);
  DeviceArray floatIndex(runtime(), DeviceArray::Type::Float32, 10), shortIndex(runtime(), DeviceArray::Type::UInt32, 9);
  DeviceArray odd(runtime(), DeviceArray::Type::Float32, 31);
  EXPECT_EQ(errorOf([&] { ev.evaluate(m, odd, V, nullptr, rgb); }), "device array L holds 31 elements; give 3 floats a row");
  EXPECT_EQ(errorOf([&] { ev.evaluate(m, L, V, nullptr, shortRgb); }), "device array rgb holds 27 elements; 10 rows need 30");
  EXPECT_EQ(errorOf([&] { ev.evaluate(m, L, V, &floatIndex, rgb); }), "device array material must be uint32");
  EXPECT_EQ(errorOf([&] { ev.evaluate(m, L, V, &shortIndex, rgb); }), "device array material holds 9 elements; 10 rows need 10");
  DeviceArray alias = V;
  EXPECT_EQ(errorOf([&] { ev.evaluate(m, L, V, nullptr, alias); }),
            "device array rgb must not be L or V; give the results their own array");
  float x[4];
  EXPECT_EQ(errorOf([&] { L.download(x, 4, 28); }), "device array of 30 elements: elements [28, 32) are out of range");
  EXPECT_EQ(errorOf([&] { rgb.upload(x, 1, 31); }), "device array of 30 elements: elements [31, 32) are out of range");
}

TEST(DeviceArrays, BadRowsAreWordedAsEvaluateWordsThem) {
  Evaluator ev(runtime(), EvalOptions{});
  const auto m = materials(2);
  Samples s = unitSamples(50, 2);
  s.V[3 * 7 + 2] = std::numeric_limits<float>::infinity();
  DeviceArray index(runtime(), DeviceArray::Type::UInt32, 50);
  DeviceArray rgb(runtime(), DeviceArray::Type::Float32, 150);
  index.upload(s.material.data(), 50);
  EXPECT_EQ(errorOf([&] { ev.evaluate(m, upload(runtime(), s.L), upload(runtime(), s.V), &index, rgb); }),
            "sample 7: Vz is not finite: inf");
  EXPECT_EQ(errorOf([&] { ev.evaluate(m, s); }), "sample 7: Vz is not finite: inf");
  s.V[3 * 7 + 2] = 0.5f;
  const std::uint32_t five = 5;
  index.upload(&five, 1, 3);
  EXPECT_EQ(errorOf([&] { ev.evaluate(m, upload(runtime(), s.L), upload(runtime(), s.V), &index, rgb); }),
            "sample 3: material index 5 out of range (2 materials)");
  std::vector<float> zeroL = s.L;
  zeroL[0] = zeroL[1] = zeroL[2] = 0;
  index.upload(s.material.data(), 50);
  EXPECT_EQ(errorOf([&] { ev.evaluate(m, upload(runtime(), zeroL), upload(runtime(), s.V), &index, rgb, true); }),
            "sample 0: L is zero");
}

}  // namespace
}  // namespace brdfcl::test
