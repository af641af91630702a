// The planes kernel's non-temporal result stores (eval_samples, batches whose results exceed the
// caches): every result lane is written, with the bits of the row kernel that the library's other
// paths use, as in the small launches of test_rows.cpp.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <random>
#include <vector>

#include "support.hpp"

namespace brdfcl::test {
namespace {

TEST(StreamStores, LargePlanesLaunchWritesEveryResultWithTheRowKernelsBits) {
  std::mt19937_64 rng(seed() + 2701);
  std::vector<MaterialParams> materials;
  for (int m = 0; m < 5; ++m) materials.push_back(randomMaterial(rng));
  // 3 planes x 4 bytes x 800,016 samples: above the 8 MiB from which the kernel streams.
  const std::size_t n = 800016;
  const Samples s = randomSamples(rng, n, materials.size());
  Evaluator ev(runtime(), EvalOptions{});
  const std::vector<float> rows = ev.evaluate(materials, s);
  SoaBatch batch(ev, materials, n);
  for (int c = 0; c < 3; ++c) {
    for (std::size_t i = 0; i < n; ++i) {
      batch.direction(c)[i] = s.L[3 * i + std::size_t(c)];
      batch.direction(3 + c)[i] = s.V[3 * i + std::size_t(c)];
      batch.resultPlane(c)[i] = std::numeric_limits<float>::quiet_NaN();
    }
  }
  std::copy(s.material.begin(), s.material.end(), batch.materialIndex());
  batch.setCount(n);
  batch.run();
  const int ulps = runtime().info().type == "CPU" ? 0 : 4;  // as PlanesKernelGivesTheRowKernelsBits
  std::size_t differ = 0, first = n;
  for (std::size_t i = 0; i < n; ++i) {
    for (int c = 0; c < 3; ++c) {
      const float got = batch.result(c)[i], want = rows[3 * i + std::size_t(c)];
      std::int32_t a, b;
      std::memcpy(&a, &got, 4);
      std::memcpy(&b, &want, 4);
      if (std::isnan(got) || std::abs(std::int64_t(a) - std::int64_t(b)) > ulps) {
        if (first == n) first = i;
        ++differ;
      }
    }
  }
  EXPECT_EQ(differ, 0u) << "first at sample " << first;
}

}  // namespace
}  // namespace brdfcl::test
