// Property tests (rapidcheck) of the library: random glTF materials and direction pairs, extremes
// included (0 and 1 exactly, denormals, FLT_MAX, huge rotations, grazing, L = +-V), through Evaluator.
// Every in-domain input gives finite f; NaN/Inf and out-of-range input gives the documented error.
#include "properties_support.hpp"

namespace {

// ---------------------------------------------------------------------------------------------
// Library: Evaluator::evaluate

// f is finite for every material and direction pair in the domain, exactly 0 at or below the
// horizon, and >= 0 except inside the documented region where the sheen albedo scaling is
// negative. One evaluate() per case: 1..6 random materials (plus the feature carriers) and
// 1..64 direction pairs under one of the 60 option sets, or, one case in four, without the
// carriers (other compiled feature sets) under the default options.
TEST(Properties, EvaluateIsFiniteAndNonNegativeOutsideTheDocumentedRegion) {
  checkProperty(250, [] {
    const bool bare = *rc::gen::weightedElement<bool>({{3, false}, {1, true}});
    const EvalOptions o = bare ? EvalOptions{} : *rc::gen::elementOf(allModes());
    auto materials = *rc::gen::resize(6, rc::gen::nonEmpty(rc::gen::container<std::vector<MaterialParams>>(material())));
    const auto pairs = *rc::gen::resize(64, rc::gen::nonEmpty(rc::gen::container<std::vector<PairSpec>>(pairSpec())));
    const std::size_t randomCount = materials.size();
    if (!bare)
      for (const auto& c : featureCarriers()) materials.push_back(c);

    Samples s;
    for (const auto& p : pairs) {
      Vec3 L, V;
      directions(p, L, V);
      s.L.insert(s.L.end(), L.begin(), L.end());
      s.V.insert(s.V.end(), V.begin(), V.end());
      s.material.push_back(p.material % std::uint32_t(randomCount));
    }
    Evaluator& ev = evaluatorFor(o);
    const std::vector<float> f = ev.evaluate(materials, s);
    RC_ASSERT(f.size() == 3 * s.size());

    for (std::size_t i = 0; i < s.size(); ++i) {
      const Vec3 L{s.L[3 * i], s.L[3 * i + 1], s.L[3 * i + 2]}, V{s.V[3 * i], s.V[3 * i + 1], s.V[3 * i + 2]};
      const MaterialParams& m = materials[s.material[i]];
      const bool below = !(L[2] > 0.0f) || !(V[2] > 0.0f);
      float scaling = NAN;  // set only inside the documented region
      const bool mayBeNegative = negativeAllowed(ev, m, L, V, &scaling);
      for (int c = 0; c < 3; ++c) {
        const float v = f[3 * i + c];
        const bool ok = std::isfinite(v) && (below ? v == 0.0f : (v >= 0.0f || mayBeNegative));
        if (!ok) {
          std::ostringstream why;
          why.precision(9);
          why << "f = " << v << " (channel " << c << ") for L " << vecText(L) << ", V " << vecText(V)
              << (below ? " (below the horizon: f must be 0)" : "") << "; material " << test::describe(m)
              << "; options " << test::describeOptions(o) << "; albedo scaling s on the host: "
              << (std::isnan(scaling) ? std::string("not computed, outside the documented region") : std::to_string(scaling));
          RC_FAIL(why.str());
        }
      }
    }
  });
}

// The property's first find, kept as a plain regression test: L and V mirrored about N at a
// grazing angle, N.L = N.V between 1e-16 and 1e-8, so that |L + V|^2 lies between the H = N
// clamp (1e-30) and float's range for the squared D denominators: f was NaN at every roughness.
TEST(Properties, GrazingNearlyOppositeDirectionsGiveFiniteF) {
  std::vector<MaterialParams> materials = featureCarriers();
  for (float roughness : {0.0f, 0.3f, 1.0f}) {
    MaterialParams m;
    m.roughness = roughness;
    m.metallic = 0.5f;
    m.clearcoat = 1.0f;
    m.clearcoatRoughness = roughness;
    materials.push_back(m);
  }
  Samples s;
  for (float z : {1e-16f, 5e-16f, 1e-14f, 1e-12f, 1e-10f, 1e-9f, 3e-9f, 1e-8f}) {
    const float t = std::sqrt(1.0f - z * z);
    s.L.insert(s.L.end(), {-t, 0.0f, z});
    s.V.insert(s.V.end(), {t, 0.0f, z});
    s.L.insert(s.L.end(), {0.0f, t, z});
    s.V.insert(s.V.end(), {0.0f, -t, z});
  }
  for (auto scaling : {SheenScaling::Min, SheenScaling::None}) {
    const auto f = evaluatorFor({SheenVisibility::Charlie, SheenDistribution::Charlie, scaling, Lobe::All})
                       .evaluateGrid(materials, s);
    for (std::size_t k = 0; k < f.size(); ++k)
      EXPECT_TRUE(std::isfinite(f[k]) && (scaling == SheenScaling::Min || f[k] >= 0.0f))
          << "f = " << f[k] << " for material " << k / 3 / s.size() << ", pair " << k / 3 % s.size() << ", L "
          << vecText({s.L[3 * (k / 3 % s.size())], s.L[3 * (k / 3 % s.size()) + 1], s.L[3 * (k / 3 % s.size()) + 2]});
  }
}

// The exception above is only as good as its box: every cell of each baked table whose bilinear
// look-up can exceed 1 lies inside it, and random look-ups (denormal and clamped arguments
// included) are finite and >= 0 everywhere.
TEST(SheenAlbedoBox, ExceedsOneOnlyInsideTheBox) {
  for (auto d : {SheenDistribution::Charlie, SheenDistribution::Ashikhmin})
    for (auto v : {SheenVisibility::Charlie, SheenVisibility::Ashikhmin}) {
      const SheenAlbedoTable& t = evaluatorFor({v, d, SheenScaling::Min, Lobe::All}).sheenAlbedo();
      const ExcessBox box = excessBox(d, v);
      const std::size_t n = t.width;
      for (std::size_t j = 0; j < n; ++j)
        for (std::size_t i = 0; i < n; ++i) {
          const float e = t.values[j * n + i];
          ASSERT_TRUE(std::isfinite(e) && e >= 0.0f) << "E = " << e << " at node " << i << ", " << j;
          if (e <= 1.0f) continue;
          // A node above 1 lifts the look-up above 1 up to the next node in each direction.
          const double reachMu = std::pow(double(std::min(i + 1, n - 1)) / double(n - 1), 2);
          const double reachR = std::pow(double(std::min(j + 1, n - 1)) / double(n - 1), 2);
          EXPECT_TRUE(reachMu <= box.muMax && reachR <= box.rMax)
              << toString(d) << " D x " << toString(v) << " V: E = " << e << " at mu " << std::pow(double(i) / (n - 1), 2)
              << ", r " << std::pow(double(j) / (n - 1), 2) << " reaches mu " << reachMu << ", r " << reachR
              << " outside the box mu <= " << box.muMax << ", r <= " << box.rMax;
        }
    }
  checkProperty(300, [] {
    const auto d = *rc::gen::element(SheenDistribution::Charlie, SheenDistribution::Ashikhmin);
    const auto v = *rc::gen::element(SheenVisibility::Charlie, SheenVisibility::Ashikhmin);
    const float mu = *unitFloat(), r = *unitFloat();
    const float e = evaluatorFor({v, d, SheenScaling::Min, Lobe::All}).sheenAlbedo().lookup(mu, r);
    RC_ASSERT(std::isfinite(e));
    RC_ASSERT(e >= 0.0f);
    const ExcessBox box = excessBox(d, v);
    if (e > 1.0f) RC_ASSERT(mu <= box.muMax && r <= box.rMax);
  });
}

// The fields of MaterialParams as the library names them in its messages.
struct Field {
  const char* name;
  float* (*at)(MaterialParams&);
  enum Kind { Unit, NonNegative, Intensity, Finite } kind;
};

void showValue(const Field& f, std::ostream& os) { os << f.name; }

const std::vector<Field>& fields() {
  static const std::vector<Field> f = {
      {"baseColor[0]", [](MaterialParams& m) { return &m.baseColor[0]; }, Field::Unit},
      {"baseColor[1]", [](MaterialParams& m) { return &m.baseColor[1]; }, Field::Unit},
      {"baseColor[2]", [](MaterialParams& m) { return &m.baseColor[2]; }, Field::Unit},
      {"metallic", [](MaterialParams& m) { return &m.metallic; }, Field::Unit},
      {"roughness", [](MaterialParams& m) { return &m.roughness; }, Field::Unit},
      {"sheenColor[0]", [](MaterialParams& m) { return &m.sheenColor[0]; }, Field::Unit},
      {"sheenColor[1]", [](MaterialParams& m) { return &m.sheenColor[1]; }, Field::Unit},
      {"sheenColor[2]", [](MaterialParams& m) { return &m.sheenColor[2]; }, Field::Unit},
      {"sheenRoughness", [](MaterialParams& m) { return &m.sheenRoughness; }, Field::Unit},
      {"draftIntensity", [](MaterialParams& m) { return &m.draftIntensity; }, Field::Intensity},
      {"draftColor[0]", [](MaterialParams& m) { return &m.draftColor[0]; }, Field::Unit},
      {"draftColor[1]", [](MaterialParams& m) { return &m.draftColor[1]; }, Field::Unit},
      {"draftColor[2]", [](MaterialParams& m) { return &m.draftColor[2]; }, Field::Unit},
      {"clearcoat", [](MaterialParams& m) { return &m.clearcoat; }, Field::Unit},
      {"clearcoatRoughness", [](MaterialParams& m) { return &m.clearcoatRoughness; }, Field::Unit},
      {"anisotropyStrength", [](MaterialParams& m) { return &m.anisotropyStrength; }, Field::Unit},
      {"anisotropyRotation", [](MaterialParams& m) { return &m.anisotropyRotation; }, Field::Finite},
      {"emissive[0]", [](MaterialParams& m) { return &m.emissive[0]; }, Field::NonNegative},
      {"emissive[1]", [](MaterialParams& m) { return &m.emissive[1]; }, Field::NonNegative},
      {"emissive[2]", [](MaterialParams& m) { return &m.emissive[2]; }, Field::NonNegative},
  };
  return f;
}

struct BadValue {
  float value;
  const char* text;  // as the message prints it
};

void showValue(const BadValue& b, std::ostream& os) { os << b.text; }

rc::Gen<BadValue> badValueFor(Field::Kind kind) {
  const float inf = INFINITY, nan = NAN;
  std::vector<BadValue> bad = {{nan, "nan"}, {-nan, "nan"}, {inf, "inf"}, {-inf, "-inf"}};
  if (kind != Field::Finite) bad.insert(bad.end(), {{-kMinDenormal, "-1e-45"}, {-0.5f, "-0.5"}, {-FLT_MAX, "-3.4028235e+38"}});
  if (kind == Field::Unit) bad.insert(bad.end(), {{1.00000012f, "1.0000001"}, {2.0f, "2"}, {FLT_MAX, "3.4028235e+38"}});
  if (kind == Field::Intensity)
    bad.insert(bad.end(), {{1.0000001e30f, "1.0000001e+30 (at most 1e+30: f would overflow float)"},
                           {FLT_MAX, "3.4028235e+38 (at most 1e+30: f would overflow float)"}});
  return rc::gen::elementOf(bad);
}

// A NaN, an infinity or an out-of-domain value in any field of any material is refused before
// anything reaches the device, with a message naming the material and the field.
TEST(Properties, MaterialOutsideTheDomainIsRejectedNamingMaterialAndField) {
  checkProperty(200, [] {
    auto materials = *rc::gen::resize(5, rc::gen::nonEmpty(rc::gen::container<std::vector<MaterialParams>>(material())));
    const std::size_t index = *rc::gen::inRange<std::size_t>(0, materials.size());
    const Field& field = *rc::gen::elementOf(fields());
    const BadValue bad = *badValueFor(field.kind);
    *field.at(materials[index]) = bad.value;
    const char* expected = field.kind == Field::Unit     ? "a number in [0, 1]"
                           : field.kind == Field::Finite ? "a finite number"
                                                         : "a number >= 0";
    const std::string want = "material " + std::to_string(index) + ": " + field.name + " must be " + expected +
                             ", got " + bad.text;
    Samples s;
    s.L = {0.0f, 0.6f, 0.8f};
    s.V = {0.0f, 0.0f, 1.0f};
    s.material = {0};
    for (bool grid : {false, true}) {
      std::string got;
      try {
        auto& ev = evaluatorFor(EvalOptions{});
        grid ? ev.evaluateGrid(materials, s) : ev.evaluate(materials, s);
      } catch (const Error& e) {
        RC_ASSERT(e.exitCode() == 2);
        got = e.what();
      }
      RC_ASSERT(got == want);
    }
  });
}

// Likewise a NaN or an infinity in any direction component of any sample.
TEST(Properties, NonFiniteDirectionIsRejectedNamingSampleAndComponent) {
  static const char* const kNames[] = {"Lx", "Ly", "Lz", "Vx", "Vy", "Vz"};
  checkProperty(200, [] {
    const auto pairs = *rc::gen::resize(32, rc::gen::nonEmpty(rc::gen::container<std::vector<PairSpec>>(pairSpec())));
    Samples s;
    for (const auto& p : pairs) {
      Vec3 L, V;
      directions(p, L, V);
      s.L.insert(s.L.end(), L.begin(), L.end());
      s.V.insert(s.V.end(), V.begin(), V.end());
      s.material.push_back(0);
    }
    const std::size_t i = *rc::gen::inRange<std::size_t>(0, s.size());
    const int k = *rc::gen::inRange(0, 6);
    const BadValue bad = *rc::gen::element(BadValue{NAN, "nan"}, BadValue{INFINITY, "inf"}, BadValue{-INFINITY, "-inf"});
    (k < 3 ? s.L[3 * i + k] : s.V[3 * i + k - 3]) = bad.value;
    const std::string want = "sample " + std::to_string(i) + ": " + kNames[k] + " is not finite: " + bad.text;
    for (bool grid : {false, true}) {
      std::string got;
      try {
        auto& ev = evaluatorFor(EvalOptions{});
        grid ? ev.evaluateGrid(featureCarriers(), s) : ev.evaluate(featureCarriers(), s);
      } catch (const Error& e) {
        got = e.what();
      }
      RC_ASSERT(got == want);
    }
  });
}

}  // namespace
