// The inlinable exp2/log2/exp/log1p of kernels/common/fastmath.h, measured on the device in ulp
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

struct Probe {
  std::vector<float> x, out;
};

Probe probe(std::vector<float> x) {
  Runtime& rt = runtime();
  auto program = testProgram(rt, "probe_fastmath.cl", "-DBRDFCL_W=1");
  Probe p{std::move(x), {}};
  p.out.resize(4 * p.x.size());
  cl::Buffer in(rt.opencl().context(), CL_MEM_READ_ONLY | CL_MEM_COPY_HOST_PTR, p.x.size() * 4, p.x.data());
  cl::Buffer out(rt.opencl().context(), CL_MEM_WRITE_ONLY, p.out.size() * 4);
  cl::KernelFunctor<cl::Buffer, cl::Buffer, cl_uint> k(program, "probe_fastmath");
  k(cl::EnqueueArgs(rt.opencl().queue(), cl::NDRange(p.x.size())), in, out, cl_uint(p.x.size()));
  rt.opencl().queue().enqueueReadBuffer(out, CL_TRUE, 0, p.out.size() * 4, p.out.data());
  return p;
}

std::vector<float> logSpaced(double lo, double hi, int n) {
  std::vector<float> v;
  for (int i = 0; i < n; ++i) v.push_back(float(lo * std::pow(hi / lo, double(i) / (n - 1))));
  return v;
}

TEST(FastMath, Exp2AndExpWithinBoundsOnTheDevice) {
  std::vector<float> x;
  for (int i = 0; i <= 20000; ++i) x.push_back(-80.0f + 100.0f * float(i) / 20000.0f);  // exp2 down to 2^-80
  const auto p = probe(x);
  double worst2 = 0, worstE = 0;
  for (std::size_t i = 0; i < x.size(); ++i) {
    worst2 = std::max(worst2, ulpError(p.out[4 * i], std::exp2(double(x[i]))));
    if (x[i] > -80.0f) worstE = std::max(worstE, ulpError(p.out[4 * i + 2], std::exp(double(x[i]))));
  }
  EXPECT_LE(worst2, 2.0);
  // exp(x) = exp2(x log2 e): rounding x log2 e costs |x| log2(e) ulp-of-argument; bound at |x| <= 80.
  EXPECT_LE(worstE, 3.0 + 80.0 * 1.4427 * 0.7);
  EXPECT_EQ(probe({-127.0f, -1000.0f}).out[0], 0.0f);  // documented flush below 2^-126
}

TEST(FastMath, Log2AndLog1pWithinBoundsOnTheDevice) {
  auto x = logSpaced(1.2e-38, 3e38, 20000);
  const auto p = probe(x);
  double worst2 = 0, worst1p = 0;
  for (std::size_t i = 0; i < x.size(); ++i) {
    const double l2 = std::log2(double(x[i]));
    // Near x = 1 log2 x -> 0 and ulp shrinks; the BRDF multiplies log2 by small exponents, so the
    // absolute error (in ulp of 1) is what matters there.
    worst2 = std::max(worst2, std::fabs(l2) < 1.0 ? std::fabs(p.out[4 * i + 1] - l2) / 0x1p-23 : ulpError(p.out[4 * i + 1], l2));
    worst1p = std::max(worst1p, ulpError(p.out[4 * i + 3], std::log1p(double(x[i]))));
  }
  EXPECT_LE(worst2, 2.0);
  EXPECT_LE(worst1p, 4.0);
  const auto edge = probe({0.0f, 1e-40f, INFINITY});
  EXPECT_TRUE(std::isinf(edge.out[1]) && edge.out[1] < 0);  // log2(0) = -inf: pow(0, c) = 0
  EXPECT_EQ(edge.out[3], 0.0f);                            // log1p(0) = 0
  EXPECT_TRUE(std::isinf(edge.out[4 * 2 + 3]));            // log1p(inf) = inf
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
