// The sampler's non-temporal row stores (sample_rows, launches whose results reach 8 MiB): every
// float of every row is written, with the bits that small launches (ordinary whole-group stores
// and the tail's) write for the same rows.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <string>
#include <vector>

#include "brdfcl/evaluator.hpp"
#include "host/src/eval/workload.hpp"
#include "support.hpp"

using namespace brdfcl;
using brdfcl::test::runtime;

namespace {

// n views from near-normal to grazing at spread azimuths, u from the counter-based generator.
void rowsOf(std::size_t n, std::vector<float>& view, std::vector<float>& u) {
  view.resize(3 * n);
  u.resize(3 * n);
  for (std::size_t i = 0; i < n; ++i) {
    const float z = 0.01f + 0.98f * float(i % 89) / 88.0f, phi = 0.93f * float(i % 1000), s = std::sqrt(1 - z * z);
    view[3 * i] = s * std::cos(phi), view[3 * i + 1] = s * std::sin(phi), view[3 * i + 2] = z;
  }
  Evaluator::drawUniforms(29, 0, n, u.data());
}

}  // namespace

TEST(SamplingStreamStores, LargeLaunchWritesTheRowsOfSmallLaunches) {
  // 7 floats x 4 bytes x 400,019 rows: above the 8 MiB from which the kernel streams, with a
  // partial group at the end; the small launches (65,536 rows, 1.8 MB) store as usual.
  const std::size_t n = 400019, small = 65536;
  std::vector<float> view, u;
  rowsOf(n, view, u);
  for (const std::string lobe : {"specular", "all"}) {
    const bench::Workload w = bench::makeWorkload(lobe, 3, 5);
    Evaluator ev(runtime(), w.options);
    std::vector<std::uint32_t> index(n);
    for (std::size_t i = 0; i < n; ++i) index[i] = std::uint32_t(i % w.materials.size());
    std::vector<float> large(7 * n, std::numeric_limits<float>::quiet_NaN());
    ev.sample(w.materials, index.data(), view.data(), u.data(), n, large.data());
    std::vector<float> parts(7 * n, std::numeric_limits<float>::quiet_NaN());
    for (std::size_t first = 0; first < n; first += small) {
      const std::size_t m = std::min(small, n - first);
      ev.sample(w.materials, index.data() + first, view.data() + 3 * first, u.data() + 3 * first, m,
                parts.data() + 7 * first);
    }
    std::size_t differ = 0, first = n, kept = 0;
    for (std::size_t i = 0; i < n; ++i) {
      kept += parts[7 * i + 3] > 0.0f;
      if (std::memcmp(&large[7 * i], &parts[7 * i], 7 * sizeof(float)) != 0 || std::isnan(large[7 * i + 3])) {
        if (first == n) first = i;
        ++differ;
      }
    }
    EXPECT_EQ(differ, 0u) << lobe << ": first at row " << first;
    EXPECT_GT(kept, n / 10) << lobe;
  }
}
