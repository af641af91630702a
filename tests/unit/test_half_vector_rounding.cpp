// The half vector's 1/|L + V| is rounded (brdf_rsqrt): at grazing mirrored pairs, where H is N and
// V.H is near 0, that rounding must not take 1 - V.H above 1, which would make F exceed 1 and the
// diffuse lobe, weighted by 1 - F, negative.
#include <gtest/gtest.h>

#include "profile_eval.hpp"
#include "support.hpp"

using namespace brdfcl;
using namespace brdfcl::test;

TEST(HalfVectorRounding, GrazingMirroredPairsLeaveEveryLobeNonNegative) {
  MaterialParams m;
  m.baseColor = {0.0f, 0.0f, 0.05f};
  m.metallic = 0.0f;
  m.roughness = 0.0f;
  m.sheenColor = {0.0f, 0.0f, 0.0f};
  // Azimuths whose mirrored pair rounds H.z above 1 under the approximate reciprocal square root.
  std::vector<std::array<float, 6>> pairs;
  for (int k = 0; k < 64; ++k) {
    const float phi = 0.0981747704f * float(k), z = 9.6057602e-16f;
    const float x = std::cos(phi), y = std::sin(phi);
    pairs.push_back({x, y, z, -x, -y, z});
  }
  pairs.push_back({0.818205416f, 0.574925959f, 9.6057602e-16f, -0.818205416f, -0.574925959f, 9.6057602e-16f});
  const Samples s = pairsOf(pairs);
  for (Lobe lobe : {Lobe::All, Lobe::Diffuse}) {
    const std::vector<float> f = evalProfile(m, Profile::Spec, lobe, s);
    for (std::size_t i = 0; i < f.size(); ++i) EXPECT_GE(f[i], 0.0f) << "pair " << i / 3 << " channel " << i % 3;
  }
}
