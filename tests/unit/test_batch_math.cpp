// The batch kernels' arithmetic per device (Runtime's Arithmetic::Batch): exact on CPUs; on GPUs
// the device's own division, sqrt and special functions with the row kernels' normalization
// done in double, which must still give the host readers' bits. BRDFCL_BATCH_MATH=fast builds
// the GPU form on PoCL, so that it is checked where CI runs. The GPUs' tuning variant of the one-lane
// material gather is checked here the same way.
#include <gtest/gtest.h>

#include <cfloat>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <random>
#include <string>
#include <vector>

#include "brdfcl/arrays.hpp"
#include "brdfcl/io.hpp"
#include "cli_eval.hpp"
#include "runtime/opencl.hpp"
#include "support.hpp"

namespace brdfcl::test {
namespace {

using Arithmetic = Runtime::OpenCL::Arithmetic;

// An environment variable set for the object's lifetime (mathOptions reads it on every build).
class ForcedEnv {
 public:
  ForcedEnv(const char* name, const char* value) : name_(name) {
    if (const char* e = std::getenv(name)) saved_ = e, had_ = true;
    ::setenv(name, value, 1);
  }
  ~ForcedEnv() { had_ ? ::setenv(name_.c_str(), saved_.c_str(), 1) : ::unsetenv(name_.c_str()); }
  ForcedEnv(const ForcedEnv&) = delete;
  ForcedEnv& operator=(const ForcedEnv&) = delete;

 private:
  std::string name_, saved_;
  bool had_ = false;
};

bool has(const std::string& s, const std::string& what) { return s.find(what) != std::string::npos; }

TEST(BatchMath, CpusBuildTheBatchKernelsExactly) {
  if (runtime().info().type != "CPU") GTEST_SKIP() << "the default device is no CPU";
  auto& cl = runtime().opencl();
  EXPECT_EQ(cl.mathOptions(Arithmetic::Batch), cl.mathOptions(Arithmetic::Exact));
  EXPECT_FALSE(has(cl.mathOptions(Arithmetic::Batch), "BRDFCL_NATIVE_MATH"));
}

TEST(BatchMath, TheGpuFormDropsTheCorrectlyRoundedFlagForTheBatchKernelsAlone) {
  ForcedEnv fast("BRDFCL_BATCH_MATH", "fast");
  auto& cl = runtime().opencl();
  const std::string batch = cl.mathOptions(Arithmetic::Batch), exact = cl.mathOptions(Arithmetic::Exact);
  EXPECT_TRUE(has(batch, "-DBRDFCL_NATIVE_MATH=1")) << batch;
  if (cl.device().getInfo<CL_DEVICE_DOUBLE_FP_CONFIG>() == 0) GTEST_SKIP() << "the device has no doubles";
  EXPECT_TRUE(has(batch, "-DBRDFCL_ROWS_FP64=1")) << batch;
  EXPECT_FALSE(has(batch, "-cl-fp32-correctly-rounded-divide-sqrt")) << batch;
  EXPECT_EQ(exact, cl.mathOptions(Arithmetic::Exact));
  EXPECT_FALSE(has(exact, "BRDFCL_")) << exact;
}

TEST(BatchMath, BuildOptionsAreAppendedForTuning) {
  ForcedEnv extra("BRDFCL_BUILD_OPTIONS", "-DBRDFCL_TUNING_PROBE=1");
  EXPECT_TRUE(has(runtime().opencl().mathOptions(Arithmetic::Exact), " -DBRDFCL_TUNING_PROBE=1"));
  EXPECT_TRUE(has(runtime().opencl().mathOptions(Arithmetic::Batch), " -DBRDFCL_TUNING_PROBE=1"));
}

// The one-lane gather's tuning variant for GPUs (BRDFCL_MATERIAL_VLOAD: the record as six 16-byte
// loads, bench/gpu/variants.txt) gives each lane its record's bits, under the spec and under an
// engine profile, which reads the record's third piece too.
TEST(BatchMath, TheRecordInSixWordsGivesEachMaterialsBits) {
  ForcedLanes forced(1);
  std::mt19937_64 rng(seed() + 96);
  std::vector<MaterialParams> materials;
  for (int m = 0; m < 64; ++m) materials.push_back(randomMaterial(rng));
  const Samples s = randomSamples(rng, 1000, materials.size());
  for (Profile p : {Profile::Spec, Profile::Filament}) {
    EvalOptions o;
    o.profile = p;
    const std::vector<float> fields = Evaluator(runtime(), o).evaluate(materials, s);
    ForcedEnv words("BRDFCL_BUILD_OPTIONS", "-DBRDFCL_MATERIAL_VLOAD=1");
    EXPECT_EQ(Evaluator(runtime(), o).evaluate(materials, s), fields) << toString(p);
  }
}

// Directions of any length, zero or subnormal components, and the extremes that take the
// rescaling branch: the double normalization must round every quotient as the host does.
std::vector<float> rawRows(std::mt19937_64& rng, std::size_t n) {
  std::vector<float> rows = {FLT_MAX, FLT_MAX, FLT_MAX, 1e-45f, 0.0f, 0.0f, 1e30f, 1e-30f, 1.0f, 0x1p-75f, 0x1p-75f, 0x1p-75f,
                             0x1p50f, 1.0f,    0x1p49f, 3.0f,   4.0f, 0.0f};
  std::uniform_real_distribution<double> u(-1.0, 1.0), exponent(-40.0, 36.0);
  while (rows.size() < 3 * n) {
    const double scale = std::pow(10.0, exponent(rng));
    for (int c = 0; c < 3; ++c) rows.push_back(float(u(rng) * scale));
    if (rows[rows.size() - 1] == 0.0f && rows[rows.size() - 2] == 0.0f && rows[rows.size() - 3] == 0.0f)
      rows.back() = FLT_TRUE_MIN;
  }
  rows.resize(3 * n);
  return rows;
}

// The row kernel's f on raw rows, bit for bit the planes kernel's f on the directions the samples
// readers normalized on the host, both built in the GPU form, at the GPU's width and the CPU's.
TEST(BatchMath, TheGpuFormNormalizesRowsToTheReadersBits) {
  ForcedEnv fast("BRDFCL_BATCH_MATH", "fast");
  if (runtime().opencl().device().getInfo<CL_DEVICE_DOUBLE_FP_CONFIG>() == 0) GTEST_SKIP() << "the device has no doubles";
  for (int w : {1, 16}) {
    ForcedLanes lanes(w);
    std::mt19937_64 rng(seed() + 977 + std::uint64_t(w));
    std::vector<MaterialParams> materials;
    for (int m = 0; m < 3; ++m) materials.push_back(randomMaterial(rng));
    const std::size_t n = 4099;
    const auto L = rawRows(rng, n), V = rawRows(rng, n);
    std::vector<std::int64_t> index(n);
    for (auto& k : index) k = std::int64_t(rng() % materials.size());
    Samples s;
    s.L.resize(3 * n);
    s.V.resize(3 * n);
    for (std::size_t i = 0; i < n; ++i) {
      const double l[3] = {L[3 * i], L[3 * i + 1], L[3 * i + 2]}, v[3] = {V[3 * i], V[3 * i + 1], V[3 * i + 2]};
      ASSERT_TRUE(normalizeDirection(l, &s.L[3 * i])) << "row " << i;
      ASSERT_TRUE(normalizeDirection(v, &s.V[3 * i])) << "row " << i;
      s.material.push_back(std::uint32_t(index[i]));
    }
    Evaluator ev(runtime(), EvalOptions{});
    const std::vector<float> want = ev.evaluate(materials, s);
    ArraySamples a;
    a.L.data = L.data();
    a.V.data = V.data();
    a.material = index.data();
    a.count = n;
    std::vector<float> got(3 * n);
    evaluateArrays(ev, materials, a, got.data());
    for (std::size_t i = 0; i < 3 * n; ++i) {
      std::uint32_t x, y;
      std::memcpy(&x, &got[i], 4);
      std::memcpy(&y, &want[i], 4);
      ASSERT_EQ(x, y) << "W = " << w << ", value " << i << " (row " << i / 3 << "): " << got[i] << " against " << want[i];
    }
  }
}

class BatchMathCli : public clieval::Cli {};

TEST_F(BatchMathCli, AnUnknownValueIsRefusedInOneLine) {
  for (const char* v : {"2", "FAST", ""}) {
    ForcedEnv bad("BRDFCL_BATCH_MATH", v);
    expectUserError(run({"bench", "--lobe", "specular", "--n", "64", "--runs", "1"}),
                    {std::string("BRDFCL_BATCH_MATH=") + v + " is not supported; use exact or fast"});
  }
}

}  // namespace
}  // namespace brdfcl::test
