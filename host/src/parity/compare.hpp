// Profile against profile (`brdfcl compare`): the relative difference of f between two parity
// profiles over dense direction sets, per lobe, the directional albedo of each, and heat maps of
// their luminance ratio. The statistics are plain data; the CLI only parses options and prints.
#pragma once
#include <array>
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "brdfcl/io.hpp"
#include "brdfcl/material.hpp"
#include "plot/plot.hpp"
#include "brdfcl/runtime.hpp"

namespace brdfcl {

// The relative difference of two sets of RGB samples (3 floats a sample). Per sample
//   d = max over r, g, b of |a - b| / max(|b|, floor)   (d = 0 where a == b, so 0 / 0 never occurs)
// over the samples whose six values are all finite. A sample with a NaN or an infinity in a or b
// is not compared but counted: in nonFiniteA, nonFiniteB (both when both) and nonFinite (either).
struct RelativeDifference {
  std::size_t samples = 0;
  std::size_t compared = 0;  // samples - nonFinite
  std::size_t nonFiniteA = 0, nonFiniteB = 0, nonFinite = 0;
  double floor = 0;
  double maxRel = 0, meanRel = 0;  // 0 when nothing was compared
  std::size_t worst = 0;           // the sample of maxRel (the first such), when compared > 0
};
// floor must be finite and > 0 (std::invalid_argument otherwise: a caller bug).
RelativeDifference relativeDifference(const float* a, const float* b, std::size_t samples, double floor);
RelativeDifference relativeDifference(const std::vector<float>& a, const std::vector<float>& b, double floor);

struct CompareOptions {
  Profile a = Profile::Spec;  // the profile under test
  Profile b = Profile::Spec;  // the reference: the denominator of d
  // In-plane grid: gridSize x gridSize cell centres of theta_L x theta_V in [0, 90) degrees.
  int gridSize = 90;
  // Out-of-plane pairs, L and V each uniform on the hemisphere, from a fixed-seed generator
  // whose sequence is the same on every platform (no std:: distributions).
  std::size_t randomPairs = 100000;
  std::uint64_t seed = 20261123;
  // floor = floorFraction x rho0 / pi, rho0 the largest finite channel of the directional albedo
  // at normal view of lobe all under either profile: a thousandth of the f of a Lambertian surface
  // as bright. Differences below it are not relative (f near 0 off the lobes' peaks).
  double floorFraction = 1e-3;
  std::vector<double> albedoViewDegrees = {0, 30, 50, 70, 80};
  bool heatMaps = true;  // also evaluate the half/difference grid and fill the log2-ratio fields
};

// The directions the statistics use, in the shading frame (N = +Z, T = +X): first the in-plane
// grid, sample iV * gridSize + iL with V = (sin tV, 0, cos tV) at phi 0 and L = (-sin tL, 0, cos tL)
// at phi 180 (the mirror configuration: the specular peak lies on tL = tV), then the random pairs.
Samples compareDirections(const CompareOptions& options);
// The half/difference grid of the second heat map (Rusinkiewicz), sample iD * n + iH at cell
// centres theta_h, theta_d in [0, 90) degrees, phi_h = 0, phi_d = 90 degrees:
// L = (cos td sin th, sin td, cos td cos th), V = (cos td sin th, -sin td, cos td cos th).
Samples halfDifferenceDirections(int n);

// Angles of one direction pair in degrees: theta from N, phi = phi_L - phi_V in (-180, 180].
struct PairAngles {
  double thetaL = 0, thetaV = 0, phi = 0;
};
PairAngles pairAngles(const float* L, const float* V);

struct LobeComparison {
  Lobe lobe = Lobe::All;
  bool zero = false;  // f == 0 at every sample under both profiles: the report skips it
  RelativeDifference diff;
  std::array<float, 3> worstL{}, worstV{};  // of diff.worst (the first sample when maxRel == 0)
  PairAngles worstAngles;
  // Directional albedo at options.albedoViewDegrees, RGB, of profile A and of profile B.
  std::vector<Rgb> albedoA, albedoB;
};

struct MaterialComparison {
  std::size_t index = 0;  // the material's index in the user's file (the CLI sets it)
  std::string name;
  double maxF = 0;      // the largest finite |f| of lobe all over the statistics' samples (reported only)
  double lambertF = 0;  // rho0 / pi (CompareOptions::floorFraction)
  double floor = 0;     // floorFraction x lambertF, at least the smallest normal float
  std::vector<LobeComparison> lobes;  // all, diffuse, specular, sheen, clearcoat, zero ones included
  // log2(max(Y_A, floor) / max(Y_B, floor)) of lobe all, Y the Rec. 709 luminance of f; NaN where
  // A or B is not finite. gridSize x gridSize, rows from the top (largest theta_V / theta_d first),
  // theta_L / theta_h rising left to right. Empty unless options.heatMaps.
  std::vector<float> inPlaneLog2Ratio, halfDiffLog2Ratio;
};

struct Comparison {
  CompareOptions options;
  std::string device;
  std::size_t inPlaneSamples = 0, randomSamples = 0;
  std::vector<MaterialComparison> materials;
};

// Evaluates every material under both profiles, each lobe on its own Evaluator, over
// compareDirections, and integrates the directional albedo (directionalAlbedo) of each.
// Throws Error for gridSize < 2 or > 4096, randomPairs > 1e8, floorFraction not in (0, 1], a view
// angle outside [0, 90), and what Evaluator throws for a bad material.
Comparison compareProfiles(Runtime& rt, const std::vector<MaterialParams>& materials, const CompareOptions& options);

// The report as text (the CLI's stdout) and as one JSON object (non-finite numbers are null).
// heatMapPaths: per material, the PNG files written (may be empty).
std::string formatComparison(const Comparison& c);
std::string comparisonJson(const Comparison& c, const std::vector<std::vector<std::string>>& heatMapPaths = {});

// The heat maps of one material: the log2 ratio in a diverging map centred on ratio 1 over
// +-ratioMapRange, each grid cell drawn as a square of pixels, theta_V (or theta_d) rising upwards,
// without text (`python -m brdfcl plot compare` draws the labelled figure).
plot::Figure drawRatioMap(const Comparison& c, const MaterialComparison& m, bool halfDiff);
// The colour range of a log2-ratio field: the first of 0.25, 0.5, 1, 2, 4, 8 that holds its
// largest finite |value| (8 beyond).
double ratioMapRange(const std::vector<float>& field);
// "<index>_<name>_<A>_vs_<B>", the name reduced to letters, digits, '-', '.' and '_'.
std::string compareFileStem(const MaterialComparison& m, Profile a, Profile b);
// Writes dir/<stem>_inplane.png and dir/<stem>_halfdiff.png (each atomically) and returns them.
// dir must exist (the CLI creates it).
std::vector<std::string> writeRatioMaps(const std::string& dir, const Comparison& c, const MaterialComparison& m);

}  // namespace brdfcl
