// Launches split into bands of rows (any image size below host memory): the spheres G-buffer and
// the shaded image are bit-identical whatever the band height, down to one row per launch.
#include <gtest/gtest.h>

#include <cstdlib>
#include <string>
#include <utility>
#include <vector>

#include "brdfcl/error.hpp"
#include "brdfcl/frame_budget.hpp"
#include "brdfcl/render.hpp"
#include "support.hpp"

using namespace brdfcl;
using namespace brdfcl::test;

namespace {

// Sets BRDFCL_MAX_LAUNCH_BYTES for one scope (bandRows reads it at every launch).
class LaunchLimit {
 public:
  explicit LaunchLimit(const std::string& bytes) { ::setenv("BRDFCL_MAX_LAUNCH_BYTES", bytes.c_str(), 1); }
  ~LaunchLimit() { ::unsetenv("BRDFCL_MAX_LAUNCH_BYTES"); }
};

TEST(Bands, RowsFollowTheDeviceLimitAndTheVariable) {
  DeviceInfo d{};
  d.maxAlloc = 1000 * 132;
  EXPECT_EQ(bandRows(d, 100, 132), 10);
  EXPECT_EQ(bandRows(d, 100000, 132), 1);  // never fewer than one row
  {
    LaunchLimit limit("13200");
    EXPECT_EQ(bandRows(d, 100, 132), 1);
  }
  for (const char* bad : {"0", "-5", "12k", "x"}) {
    LaunchLimit limit(bad);
    EXPECT_EQ(errorOf([&] { bandRows(d, 100, 132); }),
              std::string("BRDFCL_MAX_LAUNCH_BYTES=") + bad + " is not a positive number of bytes; unset it or give e.g. 1048576");
  }
}

TEST(Bands, GBufferAndShadingAreBitIdenticalForAnyBandHeight) {
  const Scene scene = spheresScene();
  const int w = 61, h = 37;  // odd sizes: the last band is short
  const GBuffer whole = renderSpheresGBuffer(runtime(), scene, w, h);
  const Image shadedWhole = Shader(runtime(), scene).shade(whole);
  for (const char* limit : {"1", "10000", "100000"}) {  // 1 row, a few rows, many rows per launch
    LaunchLimit l(limit);
    const GBuffer banded = renderSpheresGBuffer(runtime(), scene, w, h);
    EXPECT_EQ(banded.P, whole.P) << limit;
    EXPECT_EQ(banded.N, whole.N) << limit;
    EXPECT_EQ(banded.baseColor, whole.baseColor) << limit;
    EXPECT_EQ(banded.mask, whole.mask) << limit;
    EXPECT_EQ(banded.anisotropyRotation, whole.anisotropyRotation) << limit;
    EXPECT_EQ(Shader(runtime(), scene).shade(banded).rgb, shadedWhole.rgb) << limit;
  }
}

// Long frames report each band as it is done, for the CLI's progress line.
TEST(Bands, ShadeReportsEachBand) {
  const Scene scene = spheresScene();
  const GBuffer g = renderSpheresGBuffer(runtime(), scene, 61, 37);
  std::vector<std::pair<int, int>> calls;
  ShadeOptions options;
  options.progress = [&](int done, int total) { calls.emplace_back(done, total); };
  {
    LaunchLimit l("100000");  // 12 rows of 61 pixels x 132 bytes per launch: 4 bands
    Shader(runtime(), scene).shade(g, options);
  }
  EXPECT_EQ(calls, (std::vector<std::pair<int, int>>{{1, 4}, {2, 4}, {3, 4}, {4, 4}}));
  calls.clear();
  Shader(runtime(), scene).shade(g, options);
  EXPECT_EQ(calls, (std::vector<std::pair<int, int>>{{1, 1}}));
}

}  // namespace
