// Property tests (rapidcheck): random glTF materials and direction pairs, extremes included (0 and
// 1 exactly, denormals, FLT_MAX, huge rotations, grazing, L = +-V), through Evaluator and the file
// readers. Every in-domain input gives finite f; NaN/Inf and out-of-range input gives the documented error.
#include <gtest/gtest.h>
#include <rapidcheck.h>
#include <unistd.h>

#include <algorithm>
#include <array>
#include <atomic>
#include <cfloat>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <map>
#include <memory>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>
#include <tuple>
#include <vector>

#include "support.hpp"
#include "brdfcl/error.hpp"
#include "brdfcl/evaluator.hpp"
#include "brdfcl/io.hpp"

namespace fs = std::filesystem;
using namespace brdfcl;

// rapidcheck prints counterexamples with showValue, found by argument-dependent lookup.
namespace brdfcl {
void showValue(const MaterialParams& m, std::ostream& os) {
  os << test::describe(m) << (m.draftSheen ? "" : " (ratified sheen)") << ", draftIntensity " << m.draftIntensity
     << ", emissive(" << m.emissive[0] << "," << m.emissive[1] << "," << m.emissive[2] << ")";
}
void showValue(const EvalOptions& o, std::ostream& os) { os << test::describeOptions(o); }
}  // namespace brdfcl

namespace {

// ---------------------------------------------------------------------------------------------
// Running a property: reproducible by default (CI must not flake on a new random seed per run),
// seeded from BRDFCL_TEST_SEED like every other random test. RC_PARAMS still wins: set
// RC_PARAMS="seed=N" to explore, or "max_success=N" for a longer run.

std::uint64_t fnv1a(const std::string& s) {
  std::uint64_t h = 0xcbf29ce484222325ull;
  for (unsigned char c : s) h = (h ^ c) * 0x100000001b3ull;
  return h;
}

template <class Testable>
void checkProperty(int cases, Testable&& testable) {
  using namespace rc::detail;
  const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
  TestMetadata metadata;
  metadata.id = std::string(info->test_suite_name()) + "/" + info->name();
  metadata.description = info->name();
  TestParams params = configuration().testParams;
  const char* env = std::getenv("RC_PARAMS");
  const std::string rcParams = env ? env : "";
  if (rcParams.find("seed") == std::string::npos) params.seed = test::seed() ^ fnv1a(metadata.id);
  if (rcParams.find("max_success") == std::string::npos) params.maxSuccess = cases;
  const TestResult result = checkTestable(std::forward<Testable>(testable), metadata, params);
  if (!result.template is<SuccessResult>()) {
    std::ostringstream os;
    printResultMessage(result, os);
    ADD_FAILURE() << os.str() << "\nrapidcheck seed " << params.seed << " (RC_PARAMS=\"seed=" << params.seed
                  << "\" repeats this run)";
  }
}

// ---------------------------------------------------------------------------------------------
// Generators. Each mixes hand-picked extremes, uniform values and uniform bit patterns (which
// are log-uniform in magnitude, so denormals and tiny values come up as often as 0.5 does).
// Every one shrinks towards 0 or the first listed value.

float fromBits(std::uint32_t bits) {
  float f;
  std::memcpy(&f, &bits, 4);
  return f;
}

constexpr float kDenormal = 1e-40f, kMinDenormal = 1.4e-45f, kBelowOne = 0.99999994f;

// [0, 1] with 0 and 1 exactly, denormals, and the documented sheen-albedo region bounds.
rc::Gen<float> unitFloat() {
  return rc::gen::weightedOneOf<float>({
      {3, rc::gen::element(0.0f, 1.0f, kDenormal, kMinDenormal, 1e-30f, FLT_MIN, kBelowOne, 1e-7f, 0.5f, 0.05f, 0.245f,
                           0.25f, 0.415f, 0.42f)},
      {4, rc::gen::map(rc::gen::inRange<std::uint32_t>(0, (1u << 24) + 1),
                       [](std::uint32_t k) { return float(k) / 16777216.0f; })},
      {3, rc::gen::map(rc::gen::inRange<std::uint32_t>(0, 0x3f800001u), fromBits)},
  });
}

// Any finite float, either sign: radians for anisotropyRotation.
rc::Gen<float> finiteFloat() {
  return rc::gen::weightedOneOf<float>({
      {3, rc::gen::element(0.0f, 3.14159274f, -3.14159274f, 6283.18555f, 1e30f, -1e30f, 1e38f, -FLT_MAX, FLT_MAX,
                           kDenormal, -7.5f)},
      {3, rc::gen::map(rc::gen::inRange<int>(-1000000, 1000001), [](int k) { return float(k) * 1e-5f; })},
      {4, rc::gen::map(rc::gen::inRange<std::uint32_t>(0, 0xffffffffu), [](std::uint32_t b) {
         return fromBits((b & 0x7f800000u) == 0x7f800000u ? b & ~0x40000000u : b);  // keep exponents finite
       })},
  });
}

// >= 0 and finite: emissive (not part of f, but checked).
rc::Gen<float> nonNegativeFloat() {
  return rc::gen::weightedOneOf<float>({
      {6, unitFloat()},
      {2, rc::gen::map(rc::gen::inRange<int>(0, 100001), [](int k) { return float(k) * 1e-3f; })},
      {2, rc::gen::map(rc::gen::inRange<std::uint32_t>(0, 0x7f800000u), fromBits)},
  });
}

// The draft's intensityFactor: [0, kMaxDraftIntensity], the bound itself often.
rc::Gen<float> intensityFloat() {
  return rc::gen::weightedOneOf<float>({
      {5, unitFloat()},
      {2, rc::gen::element(kMaxDraftIntensity, 1e29f, 7e29f, 1e20f, 100.0f)},
      {2, rc::gen::map(rc::gen::inRange<int>(0, 100001), [](int k) { return float(k) * 1e-3f; })},
      {2, rc::gen::map(rc::gen::inRange<std::uint32_t>(0, 0x7149f2cbu), fromBits)},  // 0 .. 1e30
  });
}

rc::Gen<Rgb> rgb(rc::Gen<float> channel) {
  return rc::gen::exec([channel] { return Rgb{*channel, *channel, *channel}; });
}

// A material anywhere in the glTF domain; each layer is off (exactly 0) in about 1 case in 3.
rc::Gen<MaterialParams> material() {
  return rc::gen::exec([] {
    MaterialParams m;
    m.baseColor = *rgb(unitFloat());
    m.metallic = *unitFloat();
    m.roughness = *unitFloat();
    m.draftSheen = *rc::gen::weightedElement<bool>({{3, false}, {1, true}});
    if (*rc::gen::weightedElement<bool>({{1, false}, {2, true}})) {
      if (m.draftSheen) {
        m.draftIntensity = *intensityFloat();
        m.draftColor = *rgb(unitFloat());
      } else {
        m.sheenColor = *rgb(unitFloat());
        m.sheenRoughness = *unitFloat();
      }
    }
    if (*rc::gen::weightedElement<bool>({{1, false}, {2, true}})) {
      m.clearcoat = *unitFloat();
      m.clearcoatRoughness = *unitFloat();
    }
    if (*rc::gen::weightedElement<bool>({{1, false}, {2, true}})) {
      m.anisotropyStrength = *unitFloat();
      m.anisotropyRotation = *finiteFloat();
    }
    m.emissive = *rgb(nonNegativeFloat());
    return m;
  });
}

// A direction component before normalization: exact zeros and units, denormals, tiny, huge
// (1e30, 1e38, FLT_MAX) and anything finite.
rc::Gen<float> component() {
  return rc::gen::weightedOneOf<float>({
      {4, rc::gen::element(0.0f, 1.0f, -1.0f, kDenormal, -kDenormal, kMinDenormal, 1e-30f, -1e-30f, 1e30f, -1e30f,
                           1e38f, -1e38f, FLT_MAX, -FLT_MAX, 0.5f, -0.5f, -0.0f)},
      {3, rc::gen::map(rc::gen::inRange<int>(-1000000, 1000001), [](int k) { return float(k) * 1e-6f; })},
      {3, rc::gen::map(rc::gen::inRange<std::uint32_t>(0, 0xffffffffu), [](std::uint32_t b) {
         return fromBits((b & 0x7f800000u) == 0x7f800000u ? b & ~0x40000000u : b);
       })},
  });
}

using Vec3 = std::array<float, 3>;

// How L relates to V: the degenerate configurations get their own share.
enum class PairKind { Independent, Same, Opposite, Mirror, LightAlongN };

struct PairSpec {
  std::uint32_t material = 0;
  PairKind kind = PairKind::Independent;
  Vec3 rawL{}, rawV{};
};

void showValue(const PairSpec& p, std::ostream& os) {
  static const char* const kinds[] = {"independent", "L = V", "L = -V", "L = mirror of V", "L = N"};
  os << "material " << p.material << ", " << kinds[int(p.kind)] << ", raw L(" << p.rawL[0] << "," << p.rawL[1] << ","
     << p.rawL[2] << ") V(" << p.rawV[0] << "," << p.rawV[1] << "," << p.rawV[2] << ")";
}

rc::Gen<PairSpec> pairSpec() {
  return rc::gen::exec([] {
    PairSpec p;
    p.material = *rc::gen::inRange<std::uint32_t>(0, 64);
    p.kind = *rc::gen::weightedElement<PairKind>({{6, PairKind::Independent},
                                                  {1, PairKind::Same},
                                                  {1, PairKind::Opposite},
                                                  {1, PairKind::Mirror},
                                                  {1, PairKind::LightAlongN}});
    p.rawL = {*component(), *component(), *component()};
    p.rawV = {*component(), *component(), *component()};
    return p;
  });
}

// The unit vector a caller of the library passes (readSamples normalizes the same way: divide by
// the largest component first, so 1e38 or FLT_MAX components cannot overflow). (0, 0, 0) stays.
Vec3 unit(const Vec3& raw) {
  const double m = std::max({std::fabs(double(raw[0])), std::fabs(double(raw[1])), std::fabs(double(raw[2]))});
  if (m == 0.0) return {0.0f, 0.0f, 0.0f};
  const double x = raw[0] / m, y = raw[1] / m, z = raw[2] / m, len = std::sqrt(x * x + y * y + z * z);
  return {float(x / len), float(y / len), float(z / len)};
}

void directions(const PairSpec& p, Vec3& L, Vec3& V) {
  V = unit(p.rawV);
  switch (p.kind) {
    case PairKind::Independent: L = unit(p.rawL); break;
    case PairKind::Same: L = V; break;
    case PairKind::Opposite: L = {-V[0], -V[1], -V[2]}; break;
    case PairKind::Mirror: L = {-V[0], -V[1], V[2]}; break;
    case PairKind::LightAlongN: L = {0.0f, 0.0f, 1.0f}; break;
  }
}

const std::vector<EvalOptions>& allModes() {
  static const std::vector<EvalOptions> modes = [] {
    std::vector<EvalOptions> m;
    for (auto v : {SheenVisibility::Charlie, SheenVisibility::Ashikhmin})
      for (auto d : {SheenDistribution::Charlie, SheenDistribution::Ashikhmin})
        for (auto s : {SheenScaling::Min, SheenScaling::View, SheenScaling::None})
          for (auto l : {Lobe::All, Lobe::Diffuse, Lobe::Specular, Lobe::Sheen, Lobe::Clearcoat})
            m.push_back({v, d, s, l});
    return m;
  }();
  return modes;
}

// One Evaluator per option set for the whole binary: each owns its (cached) sheen albedo table.
// The runtime is made first so that it outlives them at exit.
Evaluator& evaluatorFor(const EvalOptions& o) {
  static Runtime& rt = test::runtime();
  static std::map<std::tuple<int, int, int, int>, std::unique_ptr<Evaluator>> evaluators;
  auto& e = evaluators[{int(o.sheenVisibility), int(o.sheenDistribution), int(o.sheenScaling), int(o.lobe)}];
  if (!e) e = std::make_unique<Evaluator>(rt, o);
  return *e;
}

// Layers no material of a batch uses are compiled out, so each feature set is its own program.
// These two materials switch every layer on: with them the 60 option sets need 60 programs (the
// ones EdgeSweep builds too), instead of 60 x 16.
std::vector<MaterialParams> featureCarriers() {
  MaterialParams ratified;
  ratified.sheenColor = {0.5f, 0.5f, 0.5f};
  ratified.sheenRoughness = 0.5f;
  ratified.clearcoat = 0.5f;
  ratified.clearcoatRoughness = 0.5f;
  ratified.anisotropyStrength = 0.5f;
  MaterialParams draft;
  draft.draftSheen = true;
  return {ratified, draft};
}

// ---------------------------------------------------------------------------------------------
// Where f may be negative: docs/model.md "Where the specs' model gains energy". The albedo scaling
// s = 1 - max3(sheenColor) E(mu, sheenRoughness) multiplies the diffuse and specular lobes, and it
// is negative only where the baked E exceeds 1. These boxes bound that region over the whole
// domain mu, r in [0, 1], the table's bilinear interpolation included
// (SheenAlbedoBox.ExceedsOneOnlyInsideTheBox checks every cell of the table); docs/model.md's table
// gives the same region on mu >= 0.01, r >= 0.05.
struct ExcessBox {
  float rMax, muMax;  // E > 1 only where r <= rMax and mu <= muMax; negative: nowhere
};

ExcessBox excessBox(SheenDistribution d, SheenVisibility v) {
  if (d == SheenDistribution::Ashikhmin) return {-1.0f, -1.0f};
  return v == SheenVisibility::Charlie ? ExcessBox{0.262f, 0.056f} : ExcessBox{0.46f, 0.097f};
}

float max3(const Rgb& c) { return std::max({c[0], c[1], c[2]}); }

// The cosines the kernels use for look-ups and visibility (docs/model.md "Clamps": BRDFCL_MIN_COS).
float floored(float cosine) { return std::max(cosine, 1e-4f); }

// True where the documented exception applies to this sample: a ratified sheen whose scaling
// enters the lobe, inside the box, and with the scaling the kernel computes (the same table,
// looked up on the host) not clearly positive. Anywhere else f must be >= 0.
bool negativeAllowed(Evaluator& ev, const MaterialParams& m, const Vec3& L, const Vec3& V, float* sOut) {
  const EvalOptions& o = ev.options();
  if (m.draftSheen || !(max3(m.sheenColor) > 0.0f) || o.sheenScaling == SheenScaling::None || o.lobe == Lobe::Sheen ||
      o.lobe == Lobe::Clearcoat)
    return false;
  const ExcessBox box = excessBox(o.sheenDistribution, o.sheenVisibility);
  const float muV = floored(V[2]), muL = floored(L[2]);
  const bool inBox = m.sheenRoughness <= box.rMax &&
                     (muV <= box.muMax || (o.sheenScaling == SheenScaling::Min && muL <= box.muMax));
  if (!inBox) return false;
  const auto& table = ev.sheenAlbedo();
  const float sView = 1.0f - max3(m.sheenColor) * table.lookup(muV, m.sheenRoughness);
  const float sLight = 1.0f - max3(m.sheenColor) * table.lookup(muL, m.sheenRoughness);
  const float s = o.sheenScaling == SheenScaling::Min ? std::min(sView, sLight) : sView;
  *sOut = s;
  // Host and device round the bilinear look-up differently; 1e-4 is far above that difference.
  return s < 1e-4f;
}

std::string vecText(const Vec3& v) {
  std::ostringstream o;
  o.precision(9);
  o << "(" << v[0] << ", " << v[1] << ", " << v[2] << ")";
  return o.str();
}

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

// ---------------------------------------------------------------------------------------------
// File readers. Each test writes its files into its own temporary directory.

std::atomic<int> dirCounter{0};

class ReaderProperties : public ::testing::Test {
 protected:
  void SetUp() override {
    const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
    dir_ = fs::temp_directory_path() /
           ("brdfcl-prop-" + std::to_string(::getpid()) + "-" + info->name() + "-" + std::to_string(dirCounter++));
    fs::remove_all(dir_);
    fs::create_directories(dir_);
  }
  void TearDown() override {
    std::error_code ec;
    fs::remove_all(dir_, ec);
  }
  std::string write(const std::string& name, const std::string& content) const {
    const std::string p = (dir_ / name).string();
    std::ofstream(p, std::ios::binary | std::ios::trunc) << content;
    return p;
  }
  fs::path dir_;
};

const char* const kColumns[] = {"material", "Lx", "Ly", "Lz", "Vx", "Vy", "Vz"};

std::string num(double x) {
  char buf[40];
  std::snprintf(buf, sizeof buf, "%.17g", x);  // round-trips a double exactly
  return buf;
}

// NPY v1.0 of `rows` x 7, float32 or float64, C or Fortran order; `cell(r, c)` gives the raw bits.
template <class Bits>
std::string npyFile(std::size_t rows, bool float32, bool fortran, Bits&& cell) {
  std::string header = std::string("{'descr': '") + (float32 ? "<f4" : "<f8") +
                       "', 'fortran_order': " + (fortran ? "True" : "False") + ", 'shape': (" + std::to_string(rows) +
                       ", 7), }";
  header.append(63 - (10 + header.size()) % 64, ' ');
  header += '\n';
  std::string out("\x93NUMPY\x01\x00", 8);
  out += char(header.size() & 0xff);
  out += char(header.size() >> 8);
  out += header;
  for (std::size_t a = 0; a < (fortran ? 7 : rows); ++a)
    for (std::size_t b = 0; b < (fortran ? rows : 7); ++b) {
      const std::uint64_t bits = fortran ? cell(b, a) : cell(a, b);
      out.append(reinterpret_cast<const char*>(&bits), float32 ? 4 : 8);  // little-endian host
    }
  return out;
}

std::uint64_t bitsOf(double v, bool float32) {
  if (float32) {
    const float f = float(v);
    std::uint32_t b;
    std::memcpy(&b, &f, 4);
    return b;
  }
  std::uint64_t b;
  std::memcpy(&b, &v, 8);
  return b;
}

struct NonFinite {
  std::uint64_t bits32, bits64;  // the same value as float32 and float64 bit patterns
  const char* csv;               // one way to write it in CSV
  const char* shown;             // how the message prints it
};

void showValue(const NonFinite& n, std::ostream& os) { os << n.csv; }

// Quiet, signalling, negative and payload NaNs; infinities; CSV spellings from_chars and strtod
// accept, and 1e999, which overflows to inf.
rc::Gen<NonFinite> nonFinite() {
  return rc::gen::element(NonFinite{0x7fc00000u, 0x7ff8000000000000ull, "nan", "nan"},
                          NonFinite{0x7f800001u, 0x7ff0000000000001ull, "NaN", "nan"},
                          NonFinite{0xffc00000u, 0xfff8000000000000ull, "-nan", "nan"},
                          NonFinite{0x7fabcdefu, 0x7ff4000000abcdefull, "NAN", "nan"},
                          NonFinite{0x7f800000u, 0x7ff0000000000000ull, "inf", "inf"},
                          NonFinite{0x7f800000u, 0x7ff0000000000000ull, "+inf", "inf"},
                          NonFinite{0x7f800000u, 0x7ff0000000000000ull, "Infinity", "inf"},
                          NonFinite{0x7f800000u, 0x7ff0000000000000ull, "1e999", "inf"},
                          NonFinite{0xff800000u, 0xfff0000000000000ull, "-inf", "-inf"},
                          NonFinite{0xff800000u, 0xfff0000000000000ull, "-1e400", "-inf"});
}

// A valid sample row: a material index and two ordinary directions, exactly representable in float.
rc::Gen<std::array<double, 7>> validRow() {
  return rc::gen::exec([] {
    std::array<double, 7> r{};
    r[0] = *rc::gen::inRange(0, 3);
    for (int c = 1; c < 7; ++c) r[c] = *rc::gen::inRange(-256, 257) / 256.0;
    r[3] = r[6] = 0.5;  // never a zero-length direction
    return r;
  });
}

// NaN or Inf anywhere in a CSV samples file is refused with the file, the 1-based line, the
// column and the text as written: "s.csv:17: field 'Lx' is not finite: '1e999'".
TEST_F(ReaderProperties, CsvNonFiniteFieldIsRejectedWithFileLineAndColumn) {
  checkProperty(200, [this] {
    const auto rows = *rc::gen::resize(40, rc::gen::nonEmpty(rc::gen::container<std::vector<std::array<double, 7>>>(validRow())));
    const std::size_t row = *rc::gen::inRange<std::size_t>(0, rows.size());
    const int col = *rc::gen::inRange(0, 7);
    const NonFinite bad = *nonFinite();
    std::string text = "material,Lx,Ly,Lz,Vx,Vy,Vz\n";
    for (std::size_t r = 0; r < rows.size(); ++r)
      for (int c = 0; c < 7; ++c) text += (r == row && c == col ? std::string(bad.csv) : num(rows[r][c])) + (c < 6 ? "," : "\n");
    const std::string path = write("s.csv", text);
    std::string got;
    try {
      readSamples(path, 3, false);
    } catch (const Error& e) {
      got = e.what();
    }
    // CSV messages quote the field as written ('1e999'); NPY ones print the value.
    RC_ASSERT(got == path + ":" + std::to_string(row + 2) + ": field '" + kColumns[col] + "' is not finite: '" + bad.csv +
                         "'");
  });
}

// The same for NPY: float32 and float64, C and Fortran order, every NaN/Inf bit pattern;
// rows are 0-based as numpy counts them.
TEST_F(ReaderProperties, NpyNonFiniteValueIsRejectedWithFileRowAndColumn) {
  checkProperty(200, [this] {
    const auto rows = *rc::gen::resize(40, rc::gen::nonEmpty(rc::gen::container<std::vector<std::array<double, 7>>>(validRow())));
    const std::size_t row = *rc::gen::inRange<std::size_t>(0, rows.size());
    const int col = *rc::gen::inRange(0, 7);
    const NonFinite bad = *nonFinite();
    const bool float32 = *rc::gen::arbitrary<bool>(), fortran = *rc::gen::arbitrary<bool>();
    const std::string path = write("s.npy", npyFile(rows.size(), float32, fortran, [&](std::size_t r, std::size_t c) {
      return r == row && int(c) == col ? (float32 ? bad.bits32 : bad.bits64) : bitsOf(rows[r][c], float32);
    }));
    std::string got;
    try {
      readSamples(path, 3, false);
    } catch (const Error& e) {
      got = e.what();
    }
    RC_ASSERT(got == path + ": row " + std::to_string(row) + ": field '" + kColumns[col] + "' is not finite: " + bad.shown);
  });
}

// A direction component as a user might write it: any finite double (for CSV and float64 NPY)
// or float (float32 NPY), denormals and DBL_MAX included.
rc::Gen<double> fileComponent(bool float32) {
  if (float32) return rc::gen::map(component(), [](float f) { return double(f); });
  return rc::gen::weightedOneOf<double>({
      {3, rc::gen::map(component(), [](float f) { return double(f); })},
      {2, rc::gen::element(1e-310, -1e-310, 4.9406564584124654e-324, 1e300, -1e300, DBL_MAX, -DBL_MAX, 1e-300)},
      {3, rc::gen::map(rc::gen::inRange<std::uint64_t>(0, ~std::uint64_t(0)), [](std::uint64_t b) {
         if ((b & 0x7ff0000000000000ull) == 0x7ff0000000000000ull) b &= ~0x4000000000000000ull;  // finite
         double d;
         std::memcpy(&d, &b, 8);
         return d;
       })},
  });
}

using Raw = std::array<double, 3>;

rc::Gen<Raw> nonZeroRaw(bool float32) {
  return rc::gen::suchThat(rc::gen::exec([float32] { return Raw{*fileComponent(float32), *fileComponent(float32), *fileComponent(float32)}; }),
                           [](const Raw& r) { return r[0] != 0.0 || r[1] != 0.0 || r[2] != 0.0; });
}

// The unit vector with the direction of `raw`, in long double: what the reader should give, to
// float precision.
std::array<long double, 3> exactUnit(const Raw& raw) {
  const long double m = std::max({std::fabs((long double)raw[0]), std::fabs((long double)raw[1]), std::fabs((long double)raw[2])});
  std::array<long double, 3> u{raw[0] / m, raw[1] / m, raw[2] / m};
  const long double len = std::sqrt(u[0] * u[0] + u[1] * u[1] + u[2] * u[2]);
  for (auto& c : u) c /= len;
  return u;
}

// Any finite, non-zero direction, however large or small its components, is accepted and
// normalized to unit length with its direction kept; the whole pipeline (reader, then
// evaluate) then gives finite f, 0 below the horizon.
TEST_F(ReaderProperties, FiniteNonZeroDirectionsAreNormalizedAndEvaluateToFiniteF) {
  checkProperty(150, [this] {
    const int format = *rc::gen::inRange(0, 3);  // CSV, float64 NPY, float32 NPY
    const bool float32 = format == 2;
    const auto n = *rc::gen::inRange(1, 25);
    std::vector<std::pair<Raw, Raw>> pairs;
    for (int i = 0; i < n; ++i) pairs.push_back({*nonZeroRaw(float32), *nonZeroRaw(float32)});
    std::string path;
    if (format == 0) {
      std::string text = "material,Lx,Ly,Lz,Vx,Vy,Vz\n";
      for (int i = 0; i < n; ++i) {
        text += std::to_string(i % 2);
        for (const Raw* d : {&pairs[i].first, &pairs[i].second})
          for (double c : *d) text += "," + num(c);
        text += "\n";
      }
      path = write("s.csv", text);
    } else {
      path = write("s.npy", npyFile(std::size_t(n), float32, false, [&](std::size_t r, std::size_t c) {
        const double v = c == 0 ? double(r % 2) : c < 4 ? pairs[r].first[c - 1] : pairs[r].second[c - 4];
        return bitsOf(v, float32);
      }));
    }
    Samples s;
    try {
      s = readSamples(path, 2, false);
    } catch (const Error& e) {
      RC_FAIL(std::string("rejected: ") + e.what());
    }
    RC_ASSERT(s.size() == std::size_t(n));
    for (int i = 0; i < n; ++i)
      for (int which = 0; which < 2; ++which) {
        const float* got = which == 0 ? &s.L[3 * i] : &s.V[3 * i];
        const auto want = exactUnit(which == 0 ? pairs[i].first : pairs[i].second);
        const double len = std::sqrt(double(got[0]) * got[0] + double(got[1]) * got[1] + double(got[2]) * got[2]);
        RC_ASSERT(std::fabs(len - 1.0) < 1e-6);
        for (int c = 0; c < 3; ++c) RC_ASSERT(std::fabs((long double)got[c] - want[c]) < 1e-6L);
      }
    const auto f = evaluatorFor(EvalOptions{}).evaluate(featureCarriers(), s);
    for (int i = 0; i < n; ++i)
      for (int c = 0; c < 3; ++c) {
        RC_ASSERT(std::isfinite(f[3 * i + c]));
        if (!(s.L[3 * i + 2] > 0.0f) || !(s.V[3 * i + 2] > 0.0f)) RC_ASSERT(f[3 * i + c] == 0.0f);
      }
  });
}

// ---------------------------------------------------------------------------------------------
// Materials JSON. JSON has no NaN literal; what can go wrong is a number out of the glTF range,
// one too large for float, one beyond double (1e999) or a value of the wrong type.

enum class Range { Unit, NonNegative, Intensity, Finite };

struct Slot {
  std::vector<std::string> keys;  // JSON object keys from the material down
  int element;                    // index in the array, or -1 for a plain number
  Range range;
  std::string path() const {
    std::string p;
    for (const auto& k : keys) p += "." + k;
    return element < 0 ? p : p + "[" + std::to_string(element) + "]";
  }
};

const std::vector<Slot>& coreSlots() {
  static const std::vector<Slot> s = [] {
    std::vector<Slot> v;
    for (int c = 0; c < 4; ++c) v.push_back({{"pbrMetallicRoughness", "baseColorFactor"}, c, Range::Unit});
    v.push_back({{"pbrMetallicRoughness", "metallicFactor"}, -1, Range::Unit});
    v.push_back({{"pbrMetallicRoughness", "roughnessFactor"}, -1, Range::Unit});
    for (int c = 0; c < 3; ++c) v.push_back({{"emissiveFactor"}, c, Range::NonNegative});
    v.push_back({{"extensions", "KHR_materials_clearcoat", "clearcoatFactor"}, -1, Range::Unit});
    v.push_back({{"extensions", "KHR_materials_clearcoat", "clearcoatRoughnessFactor"}, -1, Range::Unit});
    v.push_back({{"extensions", "KHR_materials_anisotropy", "anisotropyStrength"}, -1, Range::Unit});
    v.push_back({{"extensions", "KHR_materials_anisotropy", "anisotropyRotation"}, -1, Range::Finite});
    return v;
  }();
  return s;
}

std::vector<Slot> sheenSlots(bool draft) {
  const std::vector<std::string> ext{"extensions", "KHR_materials_sheen"};
  auto key = [&](const char* k) { auto v = ext; v.push_back(k); return v; };
  if (draft)
    return {{key("intensityFactor"), -1, Range::Intensity}, {key("colorFactor"), 0, Range::Unit},
            {key("colorFactor"), 1, Range::Unit}, {key("colorFactor"), 2, Range::Unit}};
  return {{key("sheenColorFactor"), 0, Range::Unit}, {key("sheenColorFactor"), 1, Range::Unit},
          {key("sheenColorFactor"), 2, Range::Unit}, {key("sheenRoughnessFactor"), -1, Range::Unit}};
}

// In-range values as a file would hold them: doubles, so 1e-300 (0 as a float) and values that
// round to 1.0f are there too.
rc::Gen<double> inRange(Range r) {
  const auto unit = rc::gen::weightedOneOf<double>({
      {3, rc::gen::element(0.0, 1.0, 1e-300, 1e-40, 0.5, 0.99999999999, 4.9406564584124654e-324)},
      {5, rc::gen::map(rc::gen::inRange<std::uint32_t>(0, 1000001), [](std::uint32_t k) { return k * 1e-6; })},
  });
  if (r == Range::Unit) return unit;
  if (r == Range::NonNegative)
    return rc::gen::weightedOneOf<double>({{4, unit}, {1, rc::gen::element(1e30, 3.4028234663852886e38, 7.0, 1e-310)}});
  if (r == Range::Intensity)
    return rc::gen::weightedOneOf<double>({{4, unit}, {1, rc::gen::element(1e30, 7e29, 7.0, 1e-310)}});
  return rc::gen::weightedOneOf<double>({
      {2, unit},
      {1, rc::gen::element(-1e30, 1e30, -3.4028234663852886e38, 3.4028234663852886e38, -7.5, 6283.185307179586)},
      {2, rc::gen::map(rc::gen::inRange<int>(-1000000, 1000001), [](int k) { return k * 1e-4; })},
  });
}

struct BadJson {
  std::string text;  // JSON text of the value
  std::string shown; // how the message describes it
};

void showValue(const BadJson& b, std::ostream& os) { os << b.text; }

rc::Gen<BadJson> badJson(Range r) {
  std::vector<BadJson> v = {{"\"0.5\"", "string \"0.5\""}, {"null", "null"}, {"true", "true"}, {"[0.5]", "an array of 1 element"}};
  if (r != Range::Finite) v.insert(v.end(), {{"-0.5", "-0.5"}, {"-1e-300", "-1e-300"}, {"-3", "-3"}});
  if (r == Range::Unit) v.insert(v.end(), {{"1.5", "1.5"}, {"2", "2"}, {"1.0000001", "1.0000001"}, {"1e300", "1e+300"}});
  if (r != Range::Unit) v.insert(v.end(), {{"1e300", "1e+300 (too large for float)"}, {"6.8e38", "6.8e+38 (too large for float)"}});
  if (r == Range::Intensity)
    v.insert(v.end(), {{"1e31", "1e+31 (at most 1e+30: f would overflow float)"},
                       {"3.4e38", "3.4e+38 (at most 1e+30: f would overflow float)"}});
  if (r == Range::Finite) v.push_back({"-1e300", "-1e+300 (too large for float)"});
  return rc::gen::elementOf(v);
}

const char* expectedText(Range r) {
  return r == Range::Unit ? "a number in [0, 1]" : r == Range::Finite ? "a finite number" : "a number >= 0";
}

float fieldOf(const MaterialParams& m, const Slot& s) {
  const std::string& k = s.keys.back();
  const int e = s.element;
  if (k == "baseColorFactor") return e < 3 ? m.baseColor[e] : NAN;  // alpha is checked, not kept
  if (k == "metallicFactor") return m.metallic;
  if (k == "roughnessFactor") return m.roughness;
  if (k == "emissiveFactor") return m.emissive[e];
  if (k == "clearcoatFactor") return m.clearcoat;
  if (k == "clearcoatRoughnessFactor") return m.clearcoatRoughness;
  if (k == "anisotropyStrength") return m.anisotropyStrength;
  if (k == "anisotropyRotation") return m.anisotropyRotation;
  if (k == "intensityFactor") return m.draftIntensity;
  if (k == "colorFactor") return m.draftColor[e];
  if (k == "sheenColorFactor") return m.sheenColor[e];
  return m.sheenRoughness;
}

// Random materials with a random subset of every factor: in-range values are read as the float
// nearest to them; one bad value in any of them is refused with the file, the JSON path and the
// value; 1e999 (beyond double) with the line it is on.
TEST_F(ReaderProperties, MaterialsJsonInRangeAcceptedOutOfRangeRejected) {
  checkProperty(250, [this] {
    const int count = *rc::gen::inRange(1, 5);
    struct Placed {
      int material;
      Slot slot;
      double value;
    };
    std::vector<Placed> placed;
    nlohmann::json materials = nlohmann::json::array();
    for (int i = 0; i < count; ++i) {
      const bool draft = *rc::gen::arbitrary<bool>();
      std::vector<Slot> slots = coreSlots();
      const auto sheen = sheenSlots(draft);
      slots.insert(slots.end(), sheen.begin(), sheen.end());
      nlohmann::json m = nlohmann::json::object();
      for (const auto& s : slots) {
        if (!*rc::gen::weightedElement<bool>({{1, false}, {1, true}})) continue;
        nlohmann::json* at = &m;
        for (const auto& k : s.keys) at = &(*at)[k];
        const double value = *inRange(s.range);
        if (s.element >= 0) {
          // Arrays are written whole: a missing element would be a wrong-length error instead.
          const std::size_t length = s.keys.back() == "baseColorFactor" ? 4 : 3;
          if (!at->is_array()) *at = nlohmann::json::array();
          while (at->size() < length) at->push_back(0.25);
          (*at)[std::size_t(s.element)] = value;
        } else {
          *at = value;
        }
        placed.push_back({i, s, value});
      }
      // A draft with none of its keys placed would read as ratified.
      if (draft && !m.contains("extensions")) m["extensions"]["KHR_materials_sheen"]["intensityFactor"] = 1.0;
      if (draft && !m["extensions"].contains("KHR_materials_sheen"))
        m["extensions"]["KHR_materials_sheen"]["intensityFactor"] = 1.0;
      materials.push_back(m);
    }
    // Array elements not placed explicitly hold 0.25; only explicitly placed values are checked.
    const std::string valid = nlohmann::json{{"materials", materials}}.dump();
    const bool corrupt = !placed.empty() && *rc::gen::weightedElement<bool>({{1, false}, {2, true}});
    if (!corrupt) {
      std::vector<MaterialParams> got;
      try {
        got = readMaterials(write("m.json", valid));
      } catch (const Error& e) {
        RC_FAIL(std::string("rejected: ") + e.what());
      }
      RC_ASSERT(got.size() == std::size_t(count));
      for (const auto& p : placed) {
        if (p.slot.keys.back() == "baseColorFactor" && p.slot.element == 3) continue;
        // emissiveFactor above the schema's 1 is clamped with a warning (test_emissive_factor.cpp).
        const float read = float(p.value), have = fieldOf(got[std::size_t(p.material)], p.slot);
        const float want = p.slot.keys.back() == "emissiveFactor" ? std::min(read, 1.0f) : read;
        if (!(have == want))
          RC_FAIL("materials[" + std::to_string(p.material) + "]" + p.slot.path() + ": read " + std::to_string(have) +
                  " for " + num(p.value));
      }
      return;
    }
    // One placed value becomes bad; a sentinel number marks where its text goes.
    const Placed& victim = *rc::gen::elementOf(placed);
    const bool beyondDouble = *rc::gen::weightedElement<bool>({{5, false}, {1, true}});
    const BadJson bad = beyondDouble ? BadJson{"1e999", ""} : *badJson(victim.slot.range);
    nlohmann::json doc = nlohmann::json{{"materials", materials}};
    nlohmann::json* at = &doc["materials"][std::size_t(victim.material)];
    for (const auto& k : victim.slot.keys) at = &(*at)[k];
    if (victim.slot.element >= 0) at = &(*at)[std::size_t(victim.slot.element)];
    *at = 123456789.25;
    std::string text = doc.dump(1);  // one key per line, so the line number below is meaningful
    const auto sentinel = text.find("123456789.25");
    RC_ASSERT(sentinel != std::string::npos);
    text.replace(sentinel, 12, bad.text);
    const std::string path = write("m.json", text);
    std::string got;
    try {
      readMaterials(path);
    } catch (const Error& e) {
      got = e.what();
    }
    if (beyondDouble) {
      const std::string line = std::to_string(1 + std::count(text.begin(), text.begin() + long(sentinel), '\n'));
      RC_ASSERT(got.rfind(path + ": invalid JSON: ", 0) == 0);
      RC_ASSERT(got.find("1e999") != std::string::npos);
      RC_ASSERT(got.find(" at line " + line + "; numbers must be finite") != std::string::npos);
      return;
    }
    const std::string want = path + ": materials[" + std::to_string(victim.material) + "]" + victim.slot.path() +
                             ": expected " + expectedText(victim.slot.range) + ", got " + bad.shown;
    RC_ASSERT(got == want);
  });
}

}  // namespace
