// The built-in studio environment: its softbox and strips ramp over a few texels instead of
// stepping from one texel to the next (a hard edge shows as stair steps in mirror-like spheres),
// and still reach their full radiance.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <vector>

#include "brdfcl/render.hpp"
#include "brdfcl/scene.hpp"

namespace {

std::vector<float> studio(int& w, int& h) {
  brdfcl::Environment env;
  env.builtinKind = "studio";
  return brdfcl::environmentPlanes(env, w, h);
}

}  // namespace

TEST(StudioEnvironment, LightEdgesRampOverSeveralTexels) {
  int w = 0, h = 0;
  const std::vector<float> planes = studio(w, h);
  ASSERT_EQ(w, 512);
  ASSERT_EQ(h, 256);
  const std::size_t n = std::size_t(w) * h;
  auto at = [&](int x, int y) { return planes[std::size_t(y) * w + std::size_t((x + w) % w)]; };
  // A hard edge jumps from the wall (0.06) to the softbox (6) between two texels; a ramp over
  // about 2.5 texels moves at most about 60 % of that from one texel to the next.
  float steepest = 0;
  std::size_t ramps = 0;
  for (int y = 0; y + 1 < h; ++y)
    for (int x = 0; x < w; ++x) {
      const float v = at(x, y);
      const float step = std::max(std::fabs(at(x + 1, y) - v), std::fabs(at(x, y + 1) - v));
      steepest = std::max(steepest, step);
      ramps += v > 0.5f && v < 5.5f && v != 3.0f;  // between the wall and a light's full value
    }
  EXPECT_LT(steepest, 4.5f);
  EXPECT_GT(ramps, 200u);  // every edge of the four lights ramps
  // The lights keep their radiance: the softbox reaches 6, the strips 3; grey everywhere.
  const float top = *std::max_element(planes.begin(), planes.begin() + std::ptrdiff_t(n));
  EXPECT_FLOAT_EQ(top, 6.0f);
  EXPECT_GT(std::count(planes.begin(), planes.begin() + std::ptrdiff_t(n), 3.0f), 100);
  for (std::size_t i = 0; i < n; ++i) ASSERT_EQ(planes[i], planes[n + i]);
}
