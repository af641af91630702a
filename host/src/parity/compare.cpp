// `brdfcl compare` as a library: two profiles evaluated per lobe over the in-plane grid and the
// random pairs, their relative difference and directional albedo, the text and JSON reports, and
// the log2-ratio heat maps (in-plane and half/difference) drawn with the plot layer.
#include "parity/compare.hpp"

#include <algorithm>
#include <cctype>
#include <cfloat>
#include <cmath>
#include <stdexcept>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "brdfcl/albedo.hpp"
#include "brdfcl/error.hpp"
#include "brdfcl/evaluator.hpp"
#include "io/luminance.hpp"
#include "model/profile_version.hpp"
#include "eval/splitmix64.hpp"
#include "io/messages.hpp"
#include "parity/image_diff.hpp"

namespace brdfcl {

namespace {
constexpr double kDeg = M_PI / 180.0;
constexpr Lobe kLobes[] = {Lobe::All, Lobe::Diffuse, Lobe::Specular, Lobe::Sheen, Lobe::Clearcoat};

double luminance(const float* c) { return luminance709(c[0], c[1], c[2]); }
double luminance(const Rgb& c) { return luminance(c.data()); }
bool finite3(const float* c) { return std::isfinite(c[0]) && std::isfinite(c[1]) && std::isfinite(c[2]); }

// The pairs must be the same on every platform and standard library.
struct SplitMix {
  detail::SplitMix64 bits;
  double uniform() { return bits.uniformDouble(); }
};

void pushUniformHemisphere(SplitMix& rng, std::vector<float>& out) {
  // z uniform in (0, 1] is uniform in solid angle; never 0, so no pair sits on the horizon.
  const double z = 1.0 - rng.uniform(), phi = 2 * M_PI * rng.uniform(), r = std::sqrt(std::max(0.0, 1 - z * z));
  out.insert(out.end(), {float(r * std::cos(phi)), float(r * std::sin(phi)), float(z)});
}

double cellCentreDeg(int i, int n) { return (i + 0.5) * 90.0 / n; }

void checkOptions(const CompareOptions& o) {
  if (o.gridSize < 2 || o.gridSize > 4096)
    throw Error(fmt::format("compare: grid size {} is out of range; use 2 to 4096", o.gridSize));
  if (o.randomPairs > 100000000)
    throw Error(fmt::format("compare: {} random pairs is out of range; use 0 to 100000000", o.randomPairs));
  if (!(o.floorFraction > 0 && o.floorFraction <= 1))
    throw Error(fmt::format("compare: floor fraction {} must lie in (0, 1]", o.floorFraction));
  for (double a : o.albedoViewDegrees)
    if (!(a >= 0 && a < 90)) throw Error(fmt::format("compare: albedo view angle {} deg must lie in [0, 90)", a));
}

// log2 of the floored luminance ratio per grid cell, laid out rows from the top.
std::vector<float> log2RatioField(const float* fa, const float* fb, int n, double floor) {
  std::vector<float> field(std::size_t(n) * n);
  for (int iy = 0; iy < n; ++iy)
    for (int ix = 0; ix < n; ++ix) {
      const std::size_t s = std::size_t(iy) * n + ix;
      float& out = field[std::size_t(n - 1 - iy) * n + ix];
      if (!finite3(fa + 3 * s) || !finite3(fb + 3 * s)) {
        out = NAN;
        continue;
      }
      out = float(std::log2(std::max(luminance(fa + 3 * s), floor) / std::max(luminance(fb + 3 * s), floor)));
    }
  return field;
}

std::string angleText(const LobeComparison& l) {
  if (l.diff.compared == 0 || l.diff.maxRel == 0) return "-";
  return fmt::format("({:.1f}, {:.1f}, {:.1f})", l.worstAngles.thetaL, l.worstAngles.thetaV, l.worstAngles.phi);
}

nlohmann::json number(double v) { return std::isfinite(v) ? nlohmann::json(v) : nlohmann::json(nullptr); }
}  // namespace

RelativeDifference relativeDifference(const float* a, const float* b, std::size_t samples, double floor) {
  if (!std::isfinite(floor) || !(floor > 0)) throw std::invalid_argument("relativeDifference: floor must be finite and > 0");
  RelativeDifference r;
  r.samples = samples;
  r.floor = floor;
  double sum = 0;
  for (std::size_t s = 0; s < samples; ++s) {
    const float* x = a + 3 * s;
    const float* y = b + 3 * s;
    const bool fa = finite3(x), fb = finite3(y);
    if (!fa || !fb) {
      r.nonFiniteA += !fa;
      r.nonFiniteB += !fb;
      ++r.nonFinite;
      continue;
    }
    double d = 0;
    for (int c = 0; c < 3; ++c)
      if (x[c] != y[c]) d = std::max(d, std::fabs(double(x[c]) - double(y[c])) / std::max(std::fabs(double(y[c])), floor));
    if (r.compared == 0 || d > r.maxRel) {
      r.maxRel = d;
      r.worst = s;
    }
    sum += d;
    ++r.compared;
  }
  if (r.compared > 0) r.meanRel = sum / double(r.compared);
  return r;
}

RelativeDifference relativeDifference(const std::vector<float>& a, const std::vector<float>& b, double floor) {
  if (a.size() != b.size() || a.size() % 3 != 0)
    throw std::invalid_argument("relativeDifference: a and b must hold the same number of RGB samples");
  return relativeDifference(a.data(), b.data(), a.size() / 3, floor);
}

Samples compareDirections(const CompareOptions& o) {
  checkOptions(o);
  const int n = o.gridSize;
  Samples s;
  const std::size_t total = std::size_t(n) * n + o.randomPairs;
  s.L.reserve(3 * total);
  s.V.reserve(3 * total);
  for (int iV = 0; iV < n; ++iV)
    for (int iL = 0; iL < n; ++iL) {
      const double tV = cellCentreDeg(iV, n) * kDeg, tL = cellCentreDeg(iL, n) * kDeg;
      s.V.insert(s.V.end(), {float(std::sin(tV)), 0.0f, float(std::cos(tV))});
      s.L.insert(s.L.end(), {float(-std::sin(tL)), 0.0f, float(std::cos(tL))});
    }
  SplitMix rng{{o.seed}};
  for (std::size_t i = 0; i < o.randomPairs; ++i) {
    pushUniformHemisphere(rng, s.L);
    pushUniformHemisphere(rng, s.V);
  }
  return s;
}

Samples halfDifferenceDirections(int n) {
  if (n < 1) throw std::invalid_argument("halfDifferenceDirections: n must be >= 1");
  Samples s;
  s.L.reserve(3 * std::size_t(n) * n);
  s.V.reserve(3 * std::size_t(n) * n);
  for (int iD = 0; iD < n; ++iD)
    for (int iH = 0; iH < n; ++iH) {
      const double th = cellCentreDeg(iH, n) * kDeg, td = cellCentreDeg(iD, n) * kDeg;
      const float x = float(std::cos(td) * std::sin(th)), y = float(std::sin(td)), z = float(std::cos(td) * std::cos(th));
      s.L.insert(s.L.end(), {x, y, z});
      s.V.insert(s.V.end(), {x, -y, z});
    }
  return s;
}

PairAngles pairAngles(const float* L, const float* V) {
  auto theta = [](const float* d) { return std::acos(std::clamp(double(d[2]), -1.0, 1.0)) / kDeg; };
  PairAngles a;
  a.thetaL = theta(L);
  a.thetaV = theta(V);
  double phi = (std::atan2(double(L[1]), double(L[0])) - std::atan2(double(V[1]), double(V[0]))) / kDeg;
  while (phi <= -180) phi += 360;
  while (phi > 180) phi -= 360;
  a.phi = phi;
  return a;
}

Comparison compareProfiles(Runtime& rt, const std::vector<MaterialParams>& materials, const CompareOptions& options) {
  checkOptions(options);
  if (materials.empty()) throw Error("compare: no materials to compare");
  Comparison c;
  c.options = options;
  c.device = rt.info().name;
  const int n = options.gridSize;
  const std::size_t nGrid = std::size_t(n) * n;
  c.inPlaneSamples = nGrid;
  c.randomSamples = options.randomPairs;

  Samples dirs = compareDirections(options);
  const std::size_t nStats = dirs.size();
  if (options.heatMaps) {
    const Samples hd = halfDifferenceDirections(n);
    dirs.L.insert(dirs.L.end(), hd.L.begin(), hd.L.end());
    dirs.V.insert(dirs.V.end(), hd.V.begin(), hd.V.end());
  }
  const std::size_t nAll = dirs.size();
  // mus[0] = 1 (normal view) for the floor; the reported view angles follow.
  std::vector<float> mus = {1.0f};
  for (double a : options.albedoViewDegrees) mus.push_back(float(std::cos(a * kDeg)));
  const std::size_t nViews = mus.size();

  c.materials.resize(materials.size());
  for (std::size_t m = 0; m < materials.size(); ++m) {
    c.materials[m].index = m;
    c.materials[m].name = materials[m].name;
  }
  for (Lobe lobe : kLobes) {
    std::vector<float> f[2], albedo[2];
    for (int p = 0; p < 2; ++p) {
      EvalOptions eo;
      eo.lobe = lobe;
      eo.profile = p == 0 ? options.a : options.b;
      Evaluator ev(rt, eo);
      f[p] = ev.evaluateGrid(materials, dirs);
      albedo[p] = directionalAlbedo(ev, materials, mus);
    }
    for (std::size_t m = 0; m < materials.size(); ++m) {
      MaterialComparison& mc = c.materials[m];
      const float* fa = f[0].data() + 3 * m * nAll;
      const float* fb = f[1].data() + 3 * m * nAll;
      if (lobe == Lobe::All) {
        // Statistics' samples only, so that --out (the half/difference grid) changes no number.
        double maxF = 0;
        for (const float* g : {fa, fb})
          for (std::size_t i = 0; i < 3 * nStats; ++i)
            if (std::isfinite(g[i])) maxF = std::max(maxF, double(std::fabs(g[i])));
        mc.maxF = maxF;
        // The floor scales with the f of a Lambertian surface of the material's albedo, not with
        // the peak of f: a smooth coat peaks at 1e4..1e7 1/sr at grazing mirror angles, and a
        // fraction of that would swamp the diffuse lobe. Lobe all, so a faint lobe is judged
        // against the material, not against itself.
        double rho0 = 0;
        for (int p = 0; p < 2; ++p)
          for (int ch = 0; ch < 3; ++ch) {
            const float v = albedo[p][3 * (m * nViews) + ch];
            if (std::isfinite(v)) rho0 = std::max(rho0, double(v));
          }
        mc.lambertF = rho0 / M_PI;
        mc.floor = std::max(options.floorFraction * mc.lambertF, double(FLT_MIN));
        if (options.heatMaps) {
          mc.inPlaneLog2Ratio = log2RatioField(fa, fb, n, mc.floor);
          mc.halfDiffLog2Ratio = log2RatioField(fa + 3 * nStats, fb + 3 * nStats, n, mc.floor);
        }
      }
      LobeComparison lc;
      lc.lobe = lobe;
      lc.diff = relativeDifference(fa, fb, nStats, mc.floor);
      lc.zero = lc.diff.nonFinite == 0 && std::all_of(fa, fa + 3 * nStats, [](float v) { return v == 0; }) &&
                std::all_of(fb, fb + 3 * nStats, [](float v) { return v == 0; });
      if (lc.diff.compared > 0) {
        const std::size_t w = lc.diff.worst;
        std::copy(dirs.L.begin() + 3 * w, dirs.L.begin() + 3 * w + 3, lc.worstL.begin());
        std::copy(dirs.V.begin() + 3 * w, dirs.V.begin() + 3 * w + 3, lc.worstV.begin());
        lc.worstAngles = pairAngles(lc.worstL.data(), lc.worstV.data());
      }
      for (std::size_t v = 1; v < nViews; ++v) {
        const float* ra = &albedo[0][3 * (m * nViews + v)];
        const float* rb = &albedo[1][3 * (m * nViews + v)];
        lc.albedoA.push_back({ra[0], ra[1], ra[2]});
        lc.albedoB.push_back({rb[0], rb[1], rb[2]});
      }
      mc.lobes.push_back(std::move(lc));
    }
  }
  return c;
}

std::string formatComparison(const Comparison& c) {
  using detail::formatStat;
  const CompareOptions& o = c.options;
  const char* a = toString(o.a);
  const char* b = toString(o.b);
  std::string s = fmt::format("brdfcl compare: A = {} against B = {} on {}\n", a, b, c.device);
  // The engines change between commits: the report names the pins its numbers hold for.
  s += fmt::format("A = {}\nB = {}\n", describeProfile(o.a), describeProfile(o.b));
  s += fmt::format(
      "Samples: {} in the incidence plane ({} x {} cell centres of theta_L x theta_V in [0, 90) deg, L and V at\n"
      "opposite azimuths) and {} out of it (L and V uniform on the hemisphere, seed {}).\n"
      "d = max over r,g,b of |f_A - f_B| / max(|f_B|, floor), floor = {} x rho0 / pi, rho0 the largest channel\n"
      "of the directional albedo at normal view (lobe all, either profile): the f of a Lambertian surface as bright;\n"
      "samples where A or B is NaN or infinite are counted as not finite, not compared.\n"
      "Worst case at (theta_L, theta_V, phi) in degrees, phi = phi_L - phi_V (180: the incidence plane).\n",
      c.inPlaneSamples, o.gridSize, o.gridSize, c.randomSamples, o.seed, formatStat(o.floorFraction));
  for (const MaterialComparison& m : c.materials) {
    s += fmt::format("\n[{}] {}  (rho0 / pi {} 1/sr, floor {} 1/sr, largest |f| {} 1/sr)\n", m.index,
                     detail::printable(m.name, 60), formatStat(m.lambertF), formatStat(m.floor), formatStat(m.maxF));
    s += fmt::format("  {:<10}{:>11}{:>11}{:>16}   {}\n", "lobe", "max d", "mean d", "not finite A/B", "worst at");
    std::vector<std::string> skipped;
    for (const LobeComparison& l : m.lobes) {
      if (l.zero) {
        skipped.push_back(toString(l.lobe));
        continue;
      }
      const bool any = l.diff.compared > 0;
      s += fmt::format("  {:<10}{:>11}{:>11}{:>16}   {}\n", toString(l.lobe), any ? formatStat(l.diff.maxRel) : "-",
                       any ? formatStat(l.diff.meanRel) : "-",
                       fmt::format("{} / {}", l.diff.nonFiniteA, l.diff.nonFiniteB), angleText(l));
    }
    if (!skipped.empty()) s += fmt::format("  skipped, zero under both: {}\n", fmt::join(skipped, ", "));
    s += "  directional albedo (luminance)\n";
    s += fmt::format("  {:<13}", "view");
    for (double v : o.albedoViewDegrees) s += fmt::format("{:>9}", fmt::format("{:g} deg", v));
    s += "\n";
    for (const LobeComparison& l : m.lobes) {
      if (l.zero) continue;
      for (int p = 0; p < 2; ++p) {
        const auto& al = p == 0 ? l.albedoA : l.albedoB;
        s += fmt::format("  {:<10}{:<3}", p == 0 ? toString(l.lobe) : "", p == 0 ? "A" : "B");
        for (const Rgb& rgb : al) s += fmt::format("{:>9.4f}", luminance(rgb));
        s += "\n";
      }
    }
  }
  return s;
}

namespace {
nlohmann::json engineJson(Profile p) {
  const EngineVersion v = profileEngineVersion(p);
  return {{"engine", v.engine}, {"version", v.version}};
}
}  // namespace

std::string comparisonJson(const Comparison& c, const std::vector<std::vector<std::string>>& heatMapPaths) {
  const CompareOptions& o = c.options;
  nlohmann::json mats = nlohmann::json::array();
  for (std::size_t i = 0; i < c.materials.size(); ++i) {
    const MaterialComparison& m = c.materials[i];
    nlohmann::json lobes = nlohmann::json::array(), skipped = nlohmann::json::array();
    for (const LobeComparison& l : m.lobes) {
      if (l.zero) {
        skipped.push_back(toString(l.lobe));
        continue;
      }
      nlohmann::json albA = nlohmann::json::array(), albB = nlohmann::json::array();
      nlohmann::json rgbA = nlohmann::json::array(), rgbB = nlohmann::json::array();
      for (std::size_t v = 0; v < l.albedoA.size(); ++v) {
        albA.push_back(number(luminance(l.albedoA[v])));
        albB.push_back(number(luminance(l.albedoB[v])));
        rgbA.push_back({number(l.albedoA[v][0]), number(l.albedoA[v][1]), number(l.albedoA[v][2])});
        rgbB.push_back({number(l.albedoB[v][0]), number(l.albedoB[v][1]), number(l.albedoB[v][2])});
      }
      nlohmann::json worst = nullptr;
      if (l.diff.compared > 0 && l.diff.maxRel > 0)
        worst = {{"theta_l", l.worstAngles.thetaL}, {"theta_v", l.worstAngles.thetaV}, {"phi", l.worstAngles.phi},
                 {"L", {l.worstL[0], l.worstL[1], l.worstL[2]}}, {"V", {l.worstV[0], l.worstV[1], l.worstV[2]}}};
      const bool any = l.diff.compared > 0;
      lobes.push_back({{"lobe", toString(l.lobe)},
                       {"max_rel", any ? number(l.diff.maxRel) : nlohmann::json(nullptr)},
                       {"mean_rel", any ? number(l.diff.meanRel) : nlohmann::json(nullptr)},
                       {"samples", l.diff.samples},
                       {"compared", l.diff.compared},
                       {"non_finite", l.diff.nonFinite},
                       {"non_finite_a", l.diff.nonFiniteA},
                       {"non_finite_b", l.diff.nonFiniteB},
                       {"worst", worst},
                       {"albedo_a", albA},
                       {"albedo_b", albB},
                       {"albedo_a_rgb", rgbA},
                       {"albedo_b_rgb", rgbB}});
    }
    mats.push_back({{"index", m.index},
                    {"name", m.name},
                    {"max_f", number(m.maxF)},
                    {"lambert_f", number(m.lambertF)},
                    {"floor", number(m.floor)},
                    {"lobes", lobes},
                    {"skipped_lobes", skipped},
                    {"heat_maps", i < heatMapPaths.size() ? nlohmann::json(heatMapPaths[i]) : nlohmann::json::array()}});
  }
  const nlohmann::json j = {{"profile", toString(o.a)},
                            {"against", toString(o.b)},
                            {"profile_engine", engineJson(o.a)},
                            {"against_engine", engineJson(o.b)},
                            {"device", c.device},
                            {"grid", o.gridSize},
                            {"in_plane_samples", c.inPlaneSamples},
                            {"out_of_plane_samples", c.randomSamples},
                            {"seed", o.seed},
                            {"floor_fraction", o.floorFraction},
                            {"albedo_view_degrees", o.albedoViewDegrees},
                            {"materials", mats}};
  return j.dump(2, ' ', false, nlohmann::json::error_handler_t::replace) + "\n";
}

double ratioMapRange(const std::vector<float>& field) {
  double maxAbs = 0;
  for (float v : field)
    if (std::isfinite(v)) maxAbs = std::max(maxAbs, double(std::fabs(v)));
  // A range from a short list keeps maps of different materials comparable by eye; beyond 8
  // (a factor 256) the end colours say enough.
  for (double r : {0.25, 0.5, 1.0, 2.0, 4.0, 8.0})
    if (maxAbs <= r) return r;
  return 8;
}

plot::Figure drawRatioMap(const Comparison& c, const MaterialComparison& m, bool halfDiff) {
  const std::vector<float>& field = halfDiff ? m.halfDiffLog2Ratio : m.inPlaneLog2Ratio;
  const int n = c.options.gridSize;
  if (field.size() != std::size_t(n) * n)
    throw std::invalid_argument("drawRatioMap: the comparison was made without heat maps");
  const double range = ratioMapRange(field);
  // A cell of a coarse grid would be one pixel: enlarge to about 360 pixels a side.
  const int scale = std::max(1, 360 / n), side = n * scale;
  std::vector<float> pixels(std::size_t(side) * side);
  for (int y = 0; y < side; ++y)
    for (int x = 0; x < side; ++x) pixels[std::size_t(y) * side + x] = field[std::size_t(y / scale) * n + x / scale];
  plot::HeatMap h;
  h.map = plot::ColourMap::Diverging;
  h.vMin = -range;
  h.vMax = range;
  return plot::drawHeatMap(h, side, side, pixels);
}

std::string compareFileStem(const MaterialComparison& m, Profile a, Profile b) {
  std::string name = m.name.empty() ? "material" : m.name.substr(0, 60);
  for (char& ch : name)
    if (!(std::isalnum(static_cast<unsigned char>(ch)) || ch == '-' || ch == '.' || ch == '_')) ch = '_';
  if (name.front() == '.') name.front() = '_';  // no hidden files
  return fmt::format("{}_{}_{}_vs_{}", m.index, name, toString(a), toString(b));
}

std::vector<std::string> writeRatioMaps(const std::string& dir, const Comparison& c, const MaterialComparison& m) {
  const std::string stem = (dir.empty() ? std::string(".") : dir) + "/" + compareFileStem(m, c.options.a, c.options.b);
  std::vector<std::string> paths;
  for (bool halfDiff : {false, true}) {
    const std::string path = stem + (halfDiff ? "_halfdiff.png" : "_inplane.png");
    plot::writePng(path, drawRatioMap(c, m, halfDiff).canvas);
    paths.push_back(path);
  }
  return paths;
}

}  // namespace brdfcl
