// The public API stands alone: brdfcl/brdfcl.hpp brings in no OpenCL header, and a device chosen
// by index or by name evaluates through it.
#include "brdfcl/brdfcl.hpp"

#if defined(__OPENCL_CL_H) || defined(CL_HPP_) || defined(OPENCL_CL_HPP_)
#error "brdfcl/brdfcl.hpp includes an OpenCL header: the public API names no OpenCL type"
#endif

#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <type_traits>
#include <vector>

namespace {

TEST(PublicApi, ADeviceChosenByIndexOrNameEvaluates) {
  brdfcl::Runtime first("0");
  EXPECT_EQ(first.info().index, 0u);
  brdfcl::Runtime byName(first.info().name);
  EXPECT_EQ(byName.info().name, first.info().name);
  EXPECT_FALSE(first.standardOption().empty());

  brdfcl::Evaluator ev(byName, brdfcl::EvalOptions{});
  brdfcl::Samples s;
  s.L = {0.0f, 0.6f, 0.8f};
  s.V = {0.0f, -0.6f, 0.8f};
  s.material = {0};
  const std::vector<float> rgb = ev.evaluate({brdfcl::MaterialParams{}}, s);
  ASSERT_EQ(rgb.size(), 3u);
  for (float c : rgb) EXPECT_TRUE(std::isfinite(c) && c > 0.0f) << c;
}

TEST(PublicApi, RuntimeIsAnOpaqueHandle) {
  static_assert(!std::is_copy_constructible_v<brdfcl::Runtime>);
  static_assert(sizeof(brdfcl::Runtime) == sizeof(void*), "the device's objects live behind one pointer");
}

TEST(PublicApi, AnUnknownDeviceNameIsRefused) {
  try {
    brdfcl::Runtime none("no such device 7f3a");
    FAIL() << "opened " << none.info().name;
  } catch (const brdfcl::Error& e) {
    EXPECT_NE(std::string(e.what()).find("no OpenCL device matches"), std::string::npos) << e.what();
  }
}

}  // namespace
