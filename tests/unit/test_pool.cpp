// The Evaluator's pool of batch planes (evaluator.hpp, SoaBatch::Scratch): planes a previous call
// left full of other materials' indices and longer runs' directions must give the bits a fresh
// Evaluator gives, for evaluateArrays (double-buffered, short tails), evaluate and the grid.
#include <gtest/gtest.h>

#include <cstring>
#include <random>
#include <vector>

#include "brdfcl/arrays.hpp"
#include "support.hpp"

namespace brdfcl::test {
namespace {

std::vector<float> viaArrays(Evaluator& ev, const std::vector<MaterialParams>& materials, const Samples& s,
                             std::size_t chunk) {
  std::vector<std::int64_t> index(s.material.begin(), s.material.end());
  ArraySamples a;
  a.L.data = s.L.data();
  a.V.data = s.V.data();
  a.material = index.data();
  a.count = s.size();
  std::vector<float> rgb(3 * s.size());
  evaluateArrays(ev, materials, a, rgb.data(), chunk);
  return rgb;
}

void expectSameBits(const std::vector<float>& got, const std::vector<float>& want, const std::string& what) {
  ASSERT_EQ(got.size(), want.size()) << what;
  for (std::size_t i = 0; i < got.size(); ++i)
    ASSERT_EQ(std::memcmp(&got[i], &want[i], 4), 0) << what << ": value " << i << " is " << got[i] << ", fresh "
                                                    << want[i];
}

// Rounds alternate many materials with large indices and one material with short tails, so a
// pooled plane that kept a stale index or direction past `count` would show (or fault).
TEST(Pool, ReusedPlanesGiveAFreshEvaluatorsBits) {
  std::mt19937_64 rng(seed() + 7);
  Evaluator shared(runtime(), EvalOptions{});
  const struct {
    std::size_t materials, samples, chunk;
  } rounds[] = {{32, 5000, 1024}, {1, 700, 1024}, {32, 3001, 1024}, {3, 1024, 1024}, {1, 4100, 1024}, {32, 17, 1024}};
  for (const auto& r : rounds) {
    std::vector<MaterialParams> materials;
    for (std::size_t m = 0; m < r.materials; ++m) materials.push_back(randomMaterial(rng));
    const Samples s = randomSamples(rng, r.samples, r.materials);
    Evaluator fresh(runtime(), EvalOptions{});
    const std::string what = std::to_string(r.materials) + " materials, " + std::to_string(r.samples) + " samples";
    expectSameBits(viaArrays(shared, materials, s, r.chunk), viaArrays(fresh, materials, s, r.chunk), "arrays, " + what);
    expectSameBits(shared.evaluate(materials, s), fresh.evaluate(materials, s), "evaluate, " + what);
    expectSameBits(shared.evaluateGrid(materials, s), fresh.evaluateGrid(materials, s), "grid, " + what);
  }
}

}  // namespace
}  // namespace brdfcl::test
