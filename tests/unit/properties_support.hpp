// What the property tests share (test_properties, test_properties_readers): running a rapidcheck
// property reproducibly, the generators of materials and direction pairs with their extremes,
// the documented region where f may be negative, and one Evaluator per option set.
#pragma once

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
inline void showValue(const MaterialParams& m, std::ostream& os) {
  os << test::describe(m) << (m.draftSheen ? "" : " (ratified sheen)") << ", draftIntensity " << m.draftIntensity
     << ", emissive(" << m.emissive[0] << "," << m.emissive[1] << "," << m.emissive[2] << ")";
}
inline void showValue(const EvalOptions& o, std::ostream& os) { os << test::describeOptions(o); }
}  // namespace brdfcl

namespace {

// ---------------------------------------------------------------------------------------------
// Running a property: reproducible by default (CI must not flake on a new random seed per run),
// seeded from BRDFCL_TEST_SEED like every other random test. RC_PARAMS still wins: set
// RC_PARAMS="seed=N" to explore, or "max_success=N" for a longer run.

inline std::uint64_t fnv1a(const std::string& s) {
  std::uint64_t h = 0xcbf29ce484222325ull;
  for (unsigned char c : s) h = (h ^ c) * 0x100000001b3ull;
  return h;
}

template <class Testable>
inline void checkProperty(int cases, Testable&& testable) {
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

inline float fromBits(std::uint32_t bits) {
  float f;
  std::memcpy(&f, &bits, 4);
  return f;
}

constexpr float kDenormal = 1e-40f, kMinDenormal = 1.4e-45f, kBelowOne = 0.99999994f;

// [0, 1] with 0 and 1 exactly, denormals, and the documented sheen-albedo region bounds.
inline rc::Gen<float> unitFloat() {
  return rc::gen::weightedOneOf<float>({
      {3, rc::gen::element(0.0f, 1.0f, kDenormal, kMinDenormal, 1e-30f, FLT_MIN, kBelowOne, 1e-7f, 0.5f, 0.05f, 0.245f,
                           0.25f, 0.415f, 0.42f)},
      {4, rc::gen::map(rc::gen::inRange<std::uint32_t>(0, (1u << 24) + 1),
                       [](std::uint32_t k) { return float(k) / 16777216.0f; })},
      {3, rc::gen::map(rc::gen::inRange<std::uint32_t>(0, 0x3f800001u), fromBits)},
  });
}

// Any finite float, either sign: radians for anisotropyRotation.
inline rc::Gen<float> finiteFloat() {
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
inline rc::Gen<float> nonNegativeFloat() {
  return rc::gen::weightedOneOf<float>({
      {6, unitFloat()},
      {2, rc::gen::map(rc::gen::inRange<int>(0, 100001), [](int k) { return float(k) * 1e-3f; })},
      {2, rc::gen::map(rc::gen::inRange<std::uint32_t>(0, 0x7f800000u), fromBits)},
  });
}

// The draft's intensityFactor: [0, kMaxDraftIntensity], the bound itself often.
inline rc::Gen<float> intensityFloat() {
  return rc::gen::weightedOneOf<float>({
      {5, unitFloat()},
      {2, rc::gen::element(kMaxDraftIntensity, 1e29f, 7e29f, 1e20f, 100.0f)},
      {2, rc::gen::map(rc::gen::inRange<int>(0, 100001), [](int k) { return float(k) * 1e-3f; })},
      {2, rc::gen::map(rc::gen::inRange<std::uint32_t>(0, 0x7149f2cbu), fromBits)},  // 0 .. 1e30
  });
}

inline rc::Gen<Rgb> rgb(rc::Gen<float> channel) {
  return rc::gen::exec([channel] { return Rgb{*channel, *channel, *channel}; });
}

// A material anywhere in the glTF domain; each layer is off (exactly 0) in about 1 case in 3.
inline rc::Gen<MaterialParams> material() {
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
inline rc::Gen<float> component() {
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

inline void showValue(const PairSpec& p, std::ostream& os) {
  static const char* const kinds[] = {"independent", "L = V", "L = -V", "L = mirror of V", "L = N"};
  os << "material " << p.material << ", " << kinds[int(p.kind)] << ", raw L(" << p.rawL[0] << "," << p.rawL[1] << ","
     << p.rawL[2] << ") V(" << p.rawV[0] << "," << p.rawV[1] << "," << p.rawV[2] << ")";
}

inline rc::Gen<PairSpec> pairSpec() {
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
inline Vec3 unit(const Vec3& raw) {
  const double m = std::max({std::fabs(double(raw[0])), std::fabs(double(raw[1])), std::fabs(double(raw[2]))});
  if (m == 0.0) return {0.0f, 0.0f, 0.0f};
  const double x = raw[0] / m, y = raw[1] / m, z = raw[2] / m, len = std::sqrt(x * x + y * y + z * z);
  return {float(x / len), float(y / len), float(z / len)};
}

inline void directions(const PairSpec& p, Vec3& L, Vec3& V) {
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
inline Evaluator& evaluatorFor(const EvalOptions& o) {
  static Runtime& rt = test::runtime();
  static std::map<std::tuple<int, int, int, int>, std::unique_ptr<Evaluator>> evaluators;
  auto& e = evaluators[{int(o.sheenVisibility), int(o.sheenDistribution), int(o.sheenScaling), int(o.lobe)}];
  if (!e) e = std::make_unique<Evaluator>(rt, o);
  return *e;
}

// Layers no material of a batch uses are compiled out, so each feature set is its own program.
// These two materials switch every layer on: with them the 60 option sets need 60 programs (the
// ones EdgeSweep builds too), instead of 60 x 16.
inline std::vector<MaterialParams> featureCarriers() {
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

inline ExcessBox excessBox(SheenDistribution d, SheenVisibility v) {
  if (d == SheenDistribution::Ashikhmin) return {-1.0f, -1.0f};
  return v == SheenVisibility::Charlie ? ExcessBox{0.262f, 0.056f} : ExcessBox{0.46f, 0.097f};
}

inline float max3(const Rgb& c) { return std::max({c[0], c[1], c[2]}); }

// The cosines the kernels use for look-ups and visibility (docs/model.md "Clamps": BRDFCL_MIN_COS).
inline float floored(float cosine) { return std::max(cosine, 1e-4f); }

// True where the documented exception applies to this sample: a ratified sheen whose scaling
// enters the lobe, inside the box, and with the scaling the kernel computes (the same table,
// looked up on the host) not clearly positive. Anywhere else f must be >= 0.
inline bool negativeAllowed(Evaluator& ev, const MaterialParams& m, const Vec3& L, const Vec3& V, float* sOut) {
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

inline std::string vecText(const Vec3& v) {
  std::ostringstream o;
  o.precision(9);
  o << "(" << v[0] << ", " << v[1] << ", " << v[2] << ")";
  return o.str();
}

}  // namespace
