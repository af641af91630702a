// Programs built from a caller's source text (Runtime::OpenCL::programFromSource): the test probes
// of tests/kernels are not embedded in the library, and their includes resolve from kernels/ as
// the embedded kernels' do, through the same program cache.
#include <gtest/gtest.h>

#include <map>
#include <string>

#include "brdfcl/error.hpp"
#include "host/src/runtime/opencl.hpp"
#include "support.hpp"
#include "test_kernels.hpp"

using namespace brdfcl;

namespace brdfcl::detail {
const std::map<std::string, std::string>& embeddedKernels();
}

namespace {

const std::string kProbe =
    "#include \"common/fastmath.h\"\n"
    "__kernel void twice(__global float* x) { x[get_global_id(0)] = brdf_exp2(1.0f) * x[get_global_id(0)]; }\n";

TEST(ProgramFromSource, TestProbesAreNotEmbeddedInTheLibrary) {
  const auto& files = detail::embeddedKernels();
  ASSERT_GT(files.size(), 10u);
  for (const auto& [name, text] : files) EXPECT_EQ(name.find("probe"), std::string::npos) << name << " is embedded";
  EXPECT_EQ(files.count("eval.cl"), 1u);
}

TEST(ProgramFromSource, ResolvesEmbeddedIncludesThroughTheProgramCache) {
  Runtime& rt = test::runtime();
  const cl::Program a = rt.opencl().programFromSource("twice.cl", kProbe, "-DBRDFCL_W=1");
  const cl::Program b = rt.opencl().programFromSource("twice.cl", kProbe, "-DBRDFCL_W=1");
  EXPECT_EQ(a(), b());
  const cl::Program c = rt.opencl().programFromSource("twice.cl", kProbe, "-DBRDFCL_W=1 -DBRDFCL_TEST_VARIANT=2");
  EXPECT_NE(a(), c());
  // The kernel runs: brdf_exp2 came from the embedded header.
  float x[4] = {1, 2, 3, 4};
  cl::Buffer buf(rt.opencl().context(), CL_MEM_READ_WRITE | CL_MEM_COPY_HOST_PTR, sizeof x, x);
  cl::Kernel k(a, "twice");
  k.setArg(0, buf);
  rt.opencl().queue().enqueueNDRangeKernel(k, cl::NullRange, cl::NDRange(4));
  rt.opencl().queue().enqueueReadBuffer(buf, CL_TRUE, 0, sizeof x, x);
  EXPECT_FLOAT_EQ(x[0], 2.0f);
  EXPECT_FLOAT_EQ(x[3], 8.0f);
}

TEST(ProgramFromSource, BuildErrorsNameTheTag) {
  Runtime& rt = test::runtime();
  try {
    rt.opencl().programFromSource("broken_probe.cl", "__kernel void f() { not C; }\n", "");
    FAIL() << "expected a build error";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("building broken_probe.cl"), std::string::npos) << e.what();
  }
}

TEST(ProgramFromSource, TheTestProbesBuildFromTheSourceTree) {
  Runtime& rt = test::runtime();
  EXPECT_NE(test::testProgram(rt, "probe_fastmath.cl", "-DBRDFCL_W=1")(), nullptr);
  EXPECT_NE(test::testProgram(rt, "probe_sampling.cl", "-DBRDFCL_W=16")(), nullptr);
}

}  // namespace
