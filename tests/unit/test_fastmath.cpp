// The inlinable exp2, log2, exp, log1p, log2(1 + u), 1/x and 1/sqrt(x) of kernels/common/fastmath.h, measured on the device in ulp
// against double over the ranges the BRDF feeds them; and the C++ peers of the benchmarks, which
// compile the same headers, against the kernel.
#include <gtest/gtest.h>

#include <cfloat>

#include "support.hpp"
#include "test_kernels.hpp"
#include "host/src/eval/workload.hpp"
#include "peers.hpp"
#include "host/src/runtime/opencl.hpp"

using namespace brdfcl;
using namespace brdfcl::test;

namespace {

double ulpError(float got, double want) {
  if (std::isinf(want)) return std::isinf(got) && (got > 0) == (want > 0) ? 0.0 : INFINITY;
  const double ulp = std::ldexp(1.0, std::max(std::ilogb(float(want)), FLT_MIN_EXP - 1) - 23);
  return std::fabs(double(got) - want) / ulp;
}

// One function's outputs a plane, in the probe's order.
enum Fn { kExp2, kLog2, kExp, kLog1p, kLog2_1p, kRcp, kRsqrt, kExp2NonPositive, kExpBounded, kFns };

struct Probe {
  std::vector<float> x, out;
  float at(Fn f, std::size_t i) const { return out[std::size_t(f) * x.size() + i]; }
};

// The probe at `width` lanes a work-item (1: scalar code; 16: the kernels' lanes, where PoCL's
// AVX-512 gets the hardware estimates); inputs padded to whole groups with 1.
Probe probe(std::vector<float> x, int width) {
  Runtime& rt = runtime();
  auto program = testProgram(rt, "probe_fastmath.cl", "-DBRDFCL_W=" + std::to_string(width));
  Probe p{std::move(x), {}};
  const std::size_t n = p.x.size();
  std::vector<float> in(p.x);
  in.resize((n + 15) / 16 * 16, 1.0f);
  const std::size_t padded = in.size();
  std::vector<float> out(kFns * padded);
  cl::Buffer inBuf(rt.opencl().context(), CL_MEM_READ_ONLY | CL_MEM_COPY_HOST_PTR, padded * 4, in.data());
  cl::Buffer outBuf(rt.opencl().context(), CL_MEM_WRITE_ONLY, out.size() * 4);
  cl::KernelFunctor<cl::Buffer, cl::Buffer, cl_uint> k(program, "probe_fastmath");
  k(cl::EnqueueArgs(rt.opencl().queue(), cl::NDRange(padded / std::size_t(width))), inBuf, outBuf, cl_uint(padded));
  rt.opencl().queue().enqueueReadBuffer(outBuf, CL_TRUE, 0, out.size() * 4, out.data());
  p.out.resize(kFns * n);
  for (std::size_t f = 0; f < kFns; ++f)
    std::copy_n(out.begin() + std::ptrdiff_t(f * padded), n, p.out.begin() + std::ptrdiff_t(f * n));
  return p;
}

std::vector<float> logSpaced(double lo, double hi, int n) {
  std::vector<float> v;
  for (int i = 0; i < n; ++i) v.push_back(float(lo * std::pow(hi / lo, double(i) / (n - 1))));
  return v;
}

// Each bound holds at one lane and at sixteen.
class FastMath : public ::testing::TestWithParam<int> {};
INSTANTIATE_TEST_SUITE_P(Lanes, FastMath, ::testing::Values(1, 16), [](const auto& info) {
  return "W" + std::to_string(info.param);
});

TEST_P(FastMath, Exp2AndExpWithinBoundsOnTheDevice) {
  std::vector<float> x;
  for (int i = 0; i <= 20000; ++i) x.push_back(-80.0f + 100.0f * float(i) / 20000.0f);  // exp2 down to 2^-80
  const auto p = probe(x, GetParam());
  double worst2 = 0, worstE = 0, worstB = 0;
  for (std::size_t i = 0; i < x.size(); ++i) {
    worst2 = std::max(worst2, ulpError(p.at(kExp2, i), std::exp2(double(x[i]))));
    if (x[i] > -80.0f) {
      worstE = std::max(worstE, ulpError(p.at(kExp, i), std::exp(double(x[i]))));
      worstB = std::max(worstB, ulpError(p.at(kExpBounded, i), std::exp(double(x[i]))));
    }
  }
  EXPECT_LE(worst2, 2.0);
  // exp(x) = exp2(x log2 e): rounding x log2 e costs |x| log2(e) ulp-of-argument; bound at |x| <= 80.
  EXPECT_LE(worstE, 3.0 + 80.0 * 1.4427 * 0.7);
  EXPECT_LE(worstB, 3.0 + 80.0 * 1.4427 * 0.7);
  EXPECT_EQ(probe({-127.0f, -1000.0f}, GetParam()).at(kExp2, 0), 0.0f);  // documented flush below 2^-126
}

// 2^y for y <= 0 without the clamp: the same bound down to 2^-126, 0 at and below -127 and at -inf
// (a power of 0), nothing above 2^-126 in between.
TEST_P(FastMath, Exp2OfNonPositiveWithinBoundsOnTheDevice) {
  std::vector<float> x;
  for (int i = 0; i <= 20000; ++i) x.push_back(-126.0f * float(i) / 20000.0f);
  const auto p = probe(x, GetParam());
  double worst = 0;
  for (std::size_t i = 0; i < x.size(); ++i) worst = std::max(worst, ulpError(p.at(kExp2NonPositive, i), std::exp2(double(x[i]))));
  EXPECT_LE(worst, 2.0);
  const auto edge = probe({-127.0f, -1000.0f, -INFINITY, -126.7f, -0.0f}, GetParam());
  EXPECT_EQ(edge.at(kExp2NonPositive, 0), 0.0f);
  EXPECT_EQ(edge.at(kExp2NonPositive, 1), 0.0f);
  EXPECT_EQ(edge.at(kExp2NonPositive, 2), 0.0f);
  EXPECT_LE(edge.at(kExp2NonPositive, 3), 0x1p-126f);
  EXPECT_GE(edge.at(kExp2NonPositive, 3), 0.0f);
  EXPECT_EQ(edge.at(kExp2NonPositive, 4), 1.0f);
}

TEST_P(FastMath, Log2AndLog1pWithinBoundsOnTheDevice) {
  auto x = logSpaced(1.2e-38, 3e38, 20000);
  const auto p = probe(x, GetParam());
  double worst2 = 0, worst1p = 0;
  for (std::size_t i = 0; i < x.size(); ++i) {
    const double l2 = std::log2(double(x[i]));
    // Near x = 1 log2 x -> 0 and ulp shrinks; the BRDF multiplies log2 by small exponents, so the
    // absolute error (in ulp of 1) is what matters there.
    worst2 = std::max(worst2, std::fabs(l2) < 1.0 ? std::fabs(p.at(kLog2, i) - l2) / 0x1p-23 : ulpError(p.at(kLog2, i), l2));
    worst1p = std::max(worst1p, ulpError(p.at(kLog1p, i), std::log1p(double(x[i]))));
  }
  EXPECT_LE(worst2, 2.0);
  EXPECT_LE(worst1p, 4.0);
  const auto edge = probe({0.0f, 1e-40f, INFINITY}, GetParam());
  EXPECT_TRUE(std::isinf(edge.at(kLog2, 1)) && edge.at(kLog2, 1) < 0);  // log2(0) = -inf: pow(0, c) = 0
  EXPECT_EQ(edge.at(kLog1p, 0), 0.0f);                                  // log1p(0) = 0
  EXPECT_TRUE(std::isinf(edge.at(kLog1p, 2)));                          // log1p(inf) = inf
}

// log2(1 + u), what the Charlie D raises sin^2 by: relative accuracy down to tiny u (where
// N.H -> 1), and at u = 0 and u = inf exactly.
TEST_P(FastMath, Log2Of1pWithinBoundsOnTheDevice) {
  auto x = logSpaced(1e-30, 3e38, 20000);
  const auto p = probe(x, GetParam());
  double worst = 0;
  for (std::size_t i = 0; i < x.size(); ++i)
    worst = std::max(worst, ulpError(p.at(kLog2_1p, i), std::log1p(double(x[i])) / std::log(2.0)));
  EXPECT_LE(worst, 4.0);
  const auto edge = probe({0.0f, INFINITY}, GetParam());
  EXPECT_EQ(edge.at(kLog2_1p, 0), 0.0f);
  EXPECT_TRUE(std::isinf(edge.at(kLog2_1p, 1)) && edge.at(kLog2_1p, 1) > 0);
}

// 1/x and 1/sqrt(x) over the normal floats the BRDF divides by: within float's rounding, whether a
// division and a square root or (16 lanes on AVX-512) an estimate and a Newton step.
TEST_P(FastMath, ReciprocalsWithinBoundsOnTheDevice) {
  auto x = logSpaced(1e-30, 1e30, 20000);
  const auto p = probe(x, GetParam());
  double worstRcp = 0, worstRsqrt = 0;
  for (std::size_t i = 0; i < x.size(); ++i) {
    worstRcp = std::max(worstRcp, ulpError(p.at(kRcp, i), 1.0 / double(x[i])));
    worstRsqrt = std::max(worstRsqrt, ulpError(p.at(kRsqrt, i), 1.0 / std::sqrt(double(x[i]))));
  }
  EXPECT_LE(worstRcp, 1.0);
  EXPECT_LE(worstRsqrt, 2.5);
}

// The scalar peer (no fast-math) compiles kernels/brdf/material.h as C++: it must agree with the
// kernel to float rounding, or the benchmark ratios compare different work.
TEST(Peers, ScalarPeerComputesWhatTheKernelComputes) {
  for (const auto& name : bench::workloadNames()) {
    bench::Bench b(runtime(), name, 1 << 14, 7);
    b.runKernel();
    peers::run(peers::Flavor::Scalar, name, b.peerInput());
    EXPECT_LE(b.peerDeviation(), 1e-4) << name;
    peers::run(peers::Flavor::OpenMPSimd, name, b.peerInput());
    EXPECT_LE(b.peerDeviation(), 5e-3) << name << " (fast-math peer)";
  }
}

}  // namespace
