// Test support: one shared OpenCL runtime, seeded random materials and directions in the
// specs' domain, and a comparison that keeps the worst input for the failure message.
#pragma once
#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <functional>
#include <random>
#include <sstream>
#include <string>
#include <vector>

#include "brdfcl/error.hpp"
#include "brdfcl/evaluator.hpp"
#include "reference/reference.hpp"

namespace brdfcl::test {

// AddressSanitizer reserves terabytes of shadow address space at start-up, so tests that model
// running out of memory with an address-space limit (RLIMIT_AS) cannot run under it; make
// test-asan sets allocator_may_return_null=1, so the plain allocation-failure tests still do.
#if defined(__SANITIZE_ADDRESS__)
constexpr bool kAddressSanitizer = true;
#else
constexpr bool kAddressSanitizer = false;
#endif
constexpr const char* kNoAddressSpaceLimitUnderAsan =
    "an address-space limit cannot model out-of-memory under AddressSanitizer (its shadow memory)";

// One runtime for the whole test binary: PoCL builds each kernel variant once.
inline Runtime& runtime() {
  static Runtime rt;
  return rt;
}

// The batch kernels at a forced lane width for the object's lifetime (laneShape reads
// BRDFCL_LANES on every batch); 0 leaves the device's own width.
class ForcedLanes {
 public:
  explicit ForcedLanes(int w) {
    if (const char* e = std::getenv("BRDFCL_LANES")) saved_ = e, had_ = true;
    if (w) ::setenv("BRDFCL_LANES", std::to_string(w).c_str(), 1);
  }
  ~ForcedLanes() { had_ ? ::setenv("BRDFCL_LANES", saved_.c_str(), 1) : ::unsetenv("BRDFCL_LANES"); }
  ForcedLanes(const ForcedLanes&) = delete;
  ForcedLanes& operator=(const ForcedLanes&) = delete;

 private:
  std::string saved_;
  bool had_ = false;
};

// BRDFCL_TEST_SEED regenerates every random input; failures print the seed in use.
inline std::uint64_t seed() {
  static const std::uint64_t s = [] {
    const char* e = std::getenv("BRDFCL_TEST_SEED");
    return e ? std::strtoull(e, nullptr, 10) : 20261121ull;
  }();
  return s;
}

struct Domain {
  float minRoughness = 0.05f;  // below this the documented clamps may apply
  float minCos = 0.01f;        // likewise for N.L and N.V
  double belowHorizon = 0.1;   // share of samples with L or V below the horizon
  double draftShare = 0.1;
  double zeroLayerShare = 0.2;  // share of materials without sheen / clearcoat / anisotropy
};

inline MaterialParams randomMaterial(std::mt19937_64& rng, const Domain& d = {}) {
  std::uniform_real_distribution<float> u(0.0f, 1.0f), rough(d.minRoughness, 1.0f), rot(-3.2f, 3.2f);
  auto chance = [&](double p) { return std::uniform_real_distribution<double>(0, 1)(rng) < p; };
  MaterialParams m;
  m.baseColor = {u(rng), u(rng), u(rng)};
  m.metallic = chance(0.2) ? 0.0f : chance(0.2) ? 1.0f : u(rng);
  m.roughness = rough(rng);
  if (chance(d.draftShare)) {
    m.draftSheen = true;
    m.draftIntensity = u(rng);
    m.draftColor = {u(rng), u(rng), u(rng)};
  } else if (!chance(d.zeroLayerShare)) {
    m.sheenColor = {u(rng), u(rng), u(rng)};
    m.sheenRoughness = rough(rng);
  }
  if (!chance(d.zeroLayerShare)) {
    m.clearcoat = u(rng);
    m.clearcoatRoughness = rough(rng);
  }
  if (!chance(d.zeroLayerShare)) {
    m.anisotropyStrength = u(rng);
    m.anisotropyRotation = rot(rng);
  }
  return m;
}

// A unit vector with z >= minCos (or, below the horizon, z <= 0).
inline std::array<float, 3> randomDirection(std::mt19937_64& rng, float minCos, bool below) {
  std::uniform_real_distribution<double> u(0.0, 1.0);
  const double z = below ? -u(rng) : minCos + (1.0 - minCos) * u(rng);
  const double phi = 2 * M_PI * u(rng), s = std::sqrt(std::max(0.0, 1.0 - z * z));
  return {float(s * std::cos(phi)), float(s * std::sin(phi)), float(z)};
}

inline Samples randomSamples(std::mt19937_64& rng, std::size_t n, std::size_t materialCount, const Domain& d = {}) {
  Samples s;
  std::uniform_int_distribution<std::uint32_t> pick(0, std::uint32_t(materialCount - 1));
  std::uniform_real_distribution<double> u(0.0, 1.0);
  for (std::size_t i = 0; i < n; ++i) {
    const bool below = u(rng) < d.belowHorizon;
    const bool lightBelow = below && u(rng) < 0.5;
    auto L = randomDirection(rng, d.minCos, lightBelow);
    auto V = randomDirection(rng, d.minCos, below && !lightBelow);
    s.L.insert(s.L.end(), L.begin(), L.end());
    s.V.insert(s.V.end(), V.begin(), V.end());
    if (materialCount) s.material.push_back(pick(rng));
  }
  return s;
}

inline std::string describe(const MaterialParams& m) {
  std::ostringstream o;
  o.precision(9);
  o << "baseColor(" << m.baseColor[0] << "," << m.baseColor[1] << "," << m.baseColor[2] << ") metallic " << m.metallic
    << " roughness " << m.roughness;
  if (m.draftSheen)
    o << " draft sheen intensity " << m.draftIntensity << " color(" << m.draftColor[0] << "," << m.draftColor[1]
      << "," << m.draftColor[2] << ")";
  else
    o << " sheenColor(" << m.sheenColor[0] << "," << m.sheenColor[1] << "," << m.sheenColor[2]
      << ") sheenRoughness " << m.sheenRoughness;
  o << " clearcoat " << m.clearcoat << " clearcoatRoughness " << m.clearcoatRoughness << " anisotropy "
    << m.anisotropyStrength << " rotation " << m.anisotropyRotation;
  return o.str();
}

inline std::string describeOptions(const EvalOptions& o) {
  return std::string("visibility ") + toString(o.sheenVisibility) + ", distribution " +
         toString(o.sheenDistribution) + ", scaling " + toString(o.sheenScaling) + ", lobe " + toString(o.lobe);
}

// Tracks |got - want| against tol = rel * scale + abs and remembers the worst offender.
struct WorstCase {
  double worstRatio = 0.0;  // error / tolerance; > 1 fails
  std::string report;
  std::size_t checked = 0;
  template <class Describe>
  void check(double got, double want, double scale, double rel, double abs, Describe&& what) {
    ++checked;
    const double tol = rel * scale + abs;
    const double ratio = std::isfinite(got) ? std::fabs(got - want) / tol : INFINITY;
    if (ratio > worstRatio) {
      worstRatio = ratio;
      std::ostringstream o;
      o.precision(10);
      o << "got " << got << ", reference " << want << " (|diff| " << std::fabs(got - want) << ", tolerance " << tol
        << ") for " << what();
      report = o.str();
    }
  }
};

// Runs f, which must throw brdfcl::Error with a one-line message and exit code 2; returns the message.
inline std::string errorOf(const std::function<void()>& f) {
  try {
    f();
  } catch (const Error& e) {
    EXPECT_EQ(e.exitCode(), 2);
    const std::string m = e.what();
    EXPECT_EQ(m.find('\n'), std::string::npos) << m;
    EXPECT_EQ(m.find('\r'), std::string::npos) << m;
    return m;
  } catch (const std::exception& e) {
    ADD_FAILURE() << "expected brdfcl::Error, got another exception: " << e.what();
    return {};
  }
  ADD_FAILURE() << "expected brdfcl::Error, nothing was thrown";
  return {};
}

}  // namespace brdfcl::test

#define EXPECT_CONTAINS(haystack, needle)                          \
  EXPECT_NE(std::string(haystack).find(needle), std::string::npos) \
      << "'" << (haystack) << "' lacks '" << (needle) << "'"
