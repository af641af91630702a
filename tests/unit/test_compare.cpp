// `brdfcl compare` and its library (parity/compare.hpp): the statistics against numbers computed
// here from hand-made arrays and from our own evaluations of the same directions, the direction
// sets, a profile against itself, the heat-map PNGs (the field only, no text), and the command's
// output and exit codes.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <limits>
#include <set>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>
#include <stb/stb_image.h>

#include "brdfcl/albedo.hpp"
#include "host/src/parity/compare.hpp"
#include "brdfcl/error.hpp"
#include "brdfcl/evaluator.hpp"
#include "process.hpp"
#include "support.hpp"

namespace fs = std::filesystem;
using namespace brdfcl;
using brdfcl::test::RunResult;
using brdfcl::test::ScratchDir;

namespace {
constexpr float kNaN = std::numeric_limits<float>::quiet_NaN();
constexpr float kInf = std::numeric_limits<float>::infinity();
constexpr Lobe kLobes[] = {Lobe::All, Lobe::Diffuse, Lobe::Specular, Lobe::Sheen, Lobe::Clearcoat};

// Velvet with a coat and anisotropy (every lobe), and a plain rough dielectric (no sheen, no coat).
std::vector<MaterialParams> testMaterials() {
  MaterialParams velvet;
  velvet.name = "coated velvet";
  velvet.baseColor = {0.6f, 0.1f, 0.2f};
  velvet.metallic = 0.0f;
  velvet.roughness = 0.4f;
  velvet.sheenColor = {0.9f, 0.7f, 0.8f};
  velvet.sheenRoughness = 0.5f;
  velvet.clearcoat = 0.6f;
  velvet.clearcoatRoughness = 0.2f;
  velvet.anisotropyStrength = 0.5f;
  velvet.anisotropyRotation = 0.7f;
  MaterialParams plain;
  plain.name = "plain/plastic";
  plain.baseColor = {0.2f, 0.5f, 0.8f};
  plain.metallic = 0.0f;
  plain.roughness = 0.6f;
  return {velvet, plain};
}

const char* kMaterialsJson = R"({"materials": [
  {"name": "coated velvet", "pbrMetallicRoughness": {"baseColorFactor": [0.6, 0.1, 0.2, 1], "metallicFactor": 0, "roughnessFactor": 0.4},
   "extensions": {"KHR_materials_sheen": {"sheenColorFactor": [0.9, 0.7, 0.8], "sheenRoughnessFactor": 0.5},
                  "KHR_materials_clearcoat": {"clearcoatFactor": 0.6, "clearcoatRoughnessFactor": 0.2}}},
  {"name": "plain/plastic", "pbrMetallicRoughness": {"baseColorFactor": [0.2, 0.5, 0.8, 1], "metallicFactor": 0, "roughnessFactor": 0.6}}
]})";

std::uint32_t be32(const std::string& bytes, std::size_t at) {
  std::uint32_t v = 0;
  for (int i = 0; i < 4; ++i) v = (v << 8) | static_cast<unsigned char>(bytes[at + i]);
  return v;
}

RunResult cli(const ScratchDir& dir, std::vector<std::string> args) {
  args.insert(args.begin(), BRDFCL_CLI_PATH);
  return brdfcl::test::runProcess(std::move(args), dir.dir(), dir.dir());
}

void expectOneLineError(const RunResult& r, const std::string& text) {
  EXPECT_EQ(r.status, 2) << r.describe();
  ASSERT_EQ(r.errorLines().size(), 1u) << r.describe();
  EXPECT_NE(r.errorLines()[0].find(text), std::string::npos) << "expected '" << text << "' in\n" << r.describe();
}

bool finite3(const float* c) { return std::isfinite(c[0]) && std::isfinite(c[1]) && std::isfinite(c[2]); }
}  // namespace

// ---- the statistics function ----

TEST(CompareStats, RelativeDifferenceOfHandMadeArrays) {
  // Sample 0 equal; 1: +10 % in g; 2: b below the floor, so |a - b| / floor; 3: NaN in A;
  // 4: Inf in B; 5: NaN in both; 6: 0 vs 0 (never 0 / 0); 7: -20 % in r (|d| counts).
  const std::vector<float> a = {1, 2, 3,   1, 2.2f, 3,   0.5f, 0, 0,   kNaN, 1, 1,
                                1, 1, 1,   kNaN, 0, 0,   0, 0, 0,      0.8f, 1, 1};
  const std::vector<float> b = {1, 2, 3,   1, 2, 3,      1e-9f, 0, 0,  1, 1, 1,
                                1, kInf, 1, 0, -kInf, 0, 0, 0, 0,      1, 1, 1};
  const double floor = 0.1;
  const RelativeDifference d = relativeDifference(a, b, floor);
  EXPECT_EQ(d.samples, 8u);
  EXPECT_EQ(d.nonFiniteA, 2u);
  EXPECT_EQ(d.nonFiniteB, 2u);
  EXPECT_EQ(d.nonFinite, 3u);
  EXPECT_EQ(d.compared, 5u);
  EXPECT_EQ(d.floor, floor);
  const double d1 = (2.2f - 2.0) / 2.0, d2 = (0.5 - double(1e-9f)) / floor, d7 = (1.0 - double(0.8f)) / 1.0;
  EXPECT_DOUBLE_EQ(d.maxRel, d2);
  EXPECT_EQ(d.worst, 2u);
  EXPECT_DOUBLE_EQ(d.meanRel, (0 + d1 + d2 + 0 + d7) / 5.0);

  // Nothing finite: nothing compared, the statistics stay 0 and every sample is counted.
  const RelativeDifference none = relativeDifference(std::vector<float>{kNaN, 0, 0}, std::vector<float>{0, 0, 0}, 1.0);
  EXPECT_EQ(none.compared, 0u);
  EXPECT_EQ(none.nonFinite, 1u);
  EXPECT_EQ(none.maxRel, 0.0);
  EXPECT_EQ(none.meanRel, 0.0);

  EXPECT_THROW(relativeDifference(a, b, 0.0), std::invalid_argument);
  EXPECT_THROW(relativeDifference(a, b, std::nan("")), std::invalid_argument);
  EXPECT_THROW(relativeDifference(a, std::vector<float>(3), 1.0), std::invalid_argument);
}

// ---- the direction sets ----

TEST(CompareDirections, GridIsAtLeast90x90InTheMirrorPlaneThenUniformPairs) {
  CompareOptions o;
  ASSERT_GE(o.gridSize, 90);
  o.randomPairs = 5000;
  const Samples s = compareDirections(o);
  const std::size_t nGrid = std::size_t(o.gridSize) * o.gridSize;
  ASSERT_GE(nGrid, 8100u);
  ASSERT_EQ(s.size(), nGrid + o.randomPairs);
  std::set<long> thetaL, thetaV;
  for (std::size_t i = 0; i < nGrid; ++i) {
    const float* L = &s.L[3 * i];
    const float* V = &s.V[3 * i];
    EXPECT_EQ(L[1], 0.0f);
    EXPECT_EQ(V[1], 0.0f);
    EXPECT_LT(L[0], 0.0f);  // opposite sides of the normal
    EXPECT_GT(V[0], 0.0f);
    const PairAngles a = pairAngles(L, V);
    EXPECT_NEAR(std::fabs(a.phi), 180.0, 1e-9);
    thetaL.insert(std::lround(a.thetaL * 100));
    thetaV.insert(std::lround(a.thetaV * 100));
  }
  EXPECT_EQ(thetaL.size(), std::size_t(o.gridSize));
  EXPECT_EQ(thetaV.size(), std::size_t(o.gridSize));
  EXPECT_NEAR(*thetaL.begin() / 100.0, 45.0 / o.gridSize, 1e-3);          // cell centres
  EXPECT_NEAR(*thetaL.rbegin() / 100.0, 90.0 - 45.0 / o.gridSize, 1e-3);  // 89.5 for 90 cells

  // Uniform on the hemisphere: unit, above the horizon, mean z 1/2, mean x and y 0.
  double meanZ = 0, meanX = 0, meanY = 0;
  for (std::size_t i = nGrid; i < s.size(); ++i)
    for (const auto* d : {&s.L[3 * i], &s.V[3 * i]}) {
      EXPECT_NEAR(d[0] * d[0] + d[1] * d[1] + d[2] * d[2], 1.0, 1e-5);
      EXPECT_GT(d[2], 0.0f);
      meanX += d[0];
      meanY += d[1];
      meanZ += d[2];
    }
  const double n = 2.0 * o.randomPairs;  // 3 sigma of a mean of n: about 3 x 0.29 / sqrt(n) for z
  EXPECT_NEAR(meanZ / n, 0.5, 0.015);
  EXPECT_NEAR(meanX / n, 0.0, 0.02);
  EXPECT_NEAR(meanY / n, 0.0, 0.02);

  // Fixed seed: the same pairs every time; another seed, other pairs.
  EXPECT_EQ(compareDirections(o).L, s.L);
  CompareOptions other = o;
  other.seed = o.seed + 1;
  EXPECT_NE(compareDirections(other).L, s.L);

  // Half/difference grid: H = normalize(L + V) has theta_h, and L, V are mirror images across it.
  const int hn = 10;
  const Samples hd = halfDifferenceDirections(hn);
  ASSERT_EQ(hd.size(), std::size_t(hn * hn));
  for (int iD = 0; iD < hn; ++iD)
    for (int iH = 0; iH < hn; ++iH) {
      const float* L = &hd.L[3 * (iD * hn + iH)];
      const float* V = &hd.V[3 * (iD * hn + iH)];
      double H[3] = {L[0] + V[0], L[1] + V[1], L[2] + V[2]};
      const double len = std::sqrt(H[0] * H[0] + H[1] * H[1] + H[2] * H[2]);
      EXPECT_NEAR(std::acos(H[2] / len) * 180 / M_PI, (iH + 0.5) * 90.0 / hn, 1e-3);
      EXPECT_NEAR(std::acos(std::clamp((L[0] * H[0] + L[1] * H[1] + L[2] * H[2]) / len, -1.0, 1.0)) * 180 / M_PI,
                  (iD + 0.5) * 90.0 / hn, 1e-3);
    }
}

// ---- the comparison against our own evaluation ----

TEST(Compare, StatisticsMatchTwoEvaluatorsOfTheSameDirections) {
  // Whatever the engine profile gives (NaN included), compare must report what two Evaluators
  // give for the same directions, with the statistics and floor computed here.
  const auto materials = testMaterials();
  CompareOptions o;
  o.a = Profile::Threejs;
  o.b = Profile::Spec;
  o.randomPairs = 2000;
  o.heatMaps = false;
  const Comparison c = compareProfiles(brdfcl::test::runtime(), materials, o);
  ASSERT_EQ(c.materials.size(), materials.size());
  EXPECT_EQ(c.inPlaneSamples, 8100u);
  EXPECT_EQ(c.randomSamples, 2000u);

  const Samples dirs = compareDirections(o);
  const std::size_t n = dirs.size();
  std::vector<float> mus;
  for (double a : o.albedoViewDegrees) mus.push_back(float(std::cos(a * M_PI / 180)));
  std::vector<double> floors(materials.size());
  for (Lobe lobe : kLobes) {
    std::vector<float> f[2], alb[2];
    for (int p = 0; p < 2; ++p) {
      EvalOptions eo;
      eo.lobe = lobe;
      eo.profile = p == 0 ? o.a : o.b;
      Evaluator ev(brdfcl::test::runtime(), eo);
      f[p] = ev.evaluateGrid(materials, dirs);
      alb[p] = directionalAlbedo(ev, materials, mus);
    }
    for (std::size_t m = 0; m < materials.size(); ++m) {
      const float* fa = &f[0][3 * m * n];
      const float* fb = &f[1][3 * m * n];
      if (lobe == Lobe::All) {
        double maxF = 0;
        for (std::size_t i = 0; i < 3 * n; ++i)
          for (float v : {fa[i], fb[i]})
            if (std::isfinite(v)) maxF = std::max(maxF, double(std::fabs(v)));
        EXPECT_EQ(c.materials[m].maxF, maxF);
        // rho0: the albedo at normal view (albedoViewDegrees starts at 0), largest channel of A or B.
        ASSERT_EQ(o.albedoViewDegrees[0], 0.0);
        double rho0 = 0;
        for (int p = 0; p < 2; ++p)
          for (int ch = 0; ch < 3; ++ch)
            if (std::isfinite(alb[p][3 * (m * mus.size()) + ch])) rho0 = std::max(rho0, double(alb[p][3 * (m * mus.size()) + ch]));
        EXPECT_GT(rho0, 0.05);
        floors[m] = std::max(1e-3 * (rho0 / M_PI), 1.1754943508222875e-38);
        EXPECT_DOUBLE_EQ(c.materials[m].floor, floors[m]);
      }
      double maxRel = 0, sum = 0;
      std::size_t compared = 0, nonFinite = 0, worst = 0;
      for (std::size_t s = 0; s < n; ++s) {
        if (!finite3(fa + 3 * s) || !finite3(fb + 3 * s)) {
          ++nonFinite;
          continue;
        }
        double d = 0;
        for (int ch = 0; ch < 3; ++ch) {
          const double diff = std::fabs(double(fa[3 * s + ch]) - fb[3 * s + ch]);
          if (diff > 0) d = std::max(d, diff / std::max(double(std::fabs(fb[3 * s + ch])), floors[m]));
        }
        if (compared == 0 || d > maxRel) maxRel = d, worst = s;
        sum += d;
        ++compared;
      }
      const auto it = std::find_if(c.materials[m].lobes.begin(), c.materials[m].lobes.end(),
                                   [&](const LobeComparison& l) { return l.lobe == lobe; });
      ASSERT_NE(it, c.materials[m].lobes.end()) << toString(lobe);
      const LobeComparison& l = *it;
      SCOPED_TRACE(std::string(toString(lobe)) + " of " + materials[m].name);
      EXPECT_EQ(l.diff.samples, n);
      EXPECT_EQ(l.diff.compared, compared);
      EXPECT_EQ(l.diff.nonFinite, nonFinite);
      EXPECT_DOUBLE_EQ(l.diff.maxRel, maxRel);
      if (compared > 0) {
        EXPECT_NEAR(l.diff.meanRel, sum / compared, 1e-12 * (1 + sum / compared));
        EXPECT_EQ(l.diff.worst, worst);
        const PairAngles a = pairAngles(&dirs.L[3 * worst], &dirs.V[3 * worst]);
        EXPECT_EQ(l.worstAngles.thetaL, a.thetaL);
        EXPECT_EQ(l.worstAngles.thetaV, a.thetaV);
        EXPECT_EQ(l.worstAngles.phi, a.phi);
      }
      ASSERT_EQ(l.albedoA.size(), mus.size());
      for (std::size_t v = 0; v < mus.size(); ++v)
        for (int ch = 0; ch < 3; ++ch) {
          const float ea = alb[0][3 * (m * mus.size() + v) + ch], eb = alb[1][3 * (m * mus.size() + v) + ch];
          if (std::isnan(ea)) EXPECT_TRUE(std::isnan(l.albedoA[v][ch])); else EXPECT_EQ(l.albedoA[v][ch], ea);
          if (std::isnan(eb)) EXPECT_TRUE(std::isnan(l.albedoB[v][ch])); else EXPECT_EQ(l.albedoB[v][ch], eb);
        }
    }
  }
}

TEST(Compare, ProfileAgainstItselfIsZeroEverywhere) {
  const auto materials = testMaterials();
  CompareOptions o;
  o.a = o.b = Profile::Spec;
  o.randomPairs = 1000;
  const Comparison c = compareProfiles(brdfcl::test::runtime(), materials, o);
  for (const MaterialComparison& m : c.materials) {
    SCOPED_TRACE(m.name);
    EXPECT_GT(m.maxF, 0.0);
    ASSERT_EQ(m.lobes.size(), 5u);
    for (const LobeComparison& l : m.lobes) {
      SCOPED_TRACE(toString(l.lobe));
      EXPECT_EQ(l.diff.maxRel, 0.0);
      EXPECT_EQ(l.diff.meanRel, 0.0);
      EXPECT_EQ(l.diff.nonFinite, 0u);
      EXPECT_EQ(l.diff.compared, c.inPlaneSamples + c.randomSamples);
      for (std::size_t v = 0; v < l.albedoA.size(); ++v) EXPECT_EQ(l.albedoA[v], l.albedoB[v]);
    }
    ASSERT_EQ(m.inPlaneLog2Ratio.size(), 8100u);
    ASSERT_EQ(m.halfDiffLog2Ratio.size(), 8100u);
    for (float v : m.inPlaneLog2Ratio) ASSERT_EQ(v, 0.0f);
    for (float v : m.halfDiffLog2Ratio) ASSERT_EQ(v, 0.0f);
  }
  // Zero lobes are flagged (and skipped by the report): the plain material has no sheen or coat.
  auto zero = [&](std::size_t m, Lobe l) { return c.materials[m].lobes[std::size_t(l)].zero; };
  EXPECT_FALSE(zero(0, Lobe::All));
  EXPECT_FALSE(zero(0, Lobe::Sheen));
  EXPECT_FALSE(zero(0, Lobe::Clearcoat));
  EXPECT_FALSE(zero(1, Lobe::Diffuse));
  EXPECT_TRUE(zero(1, Lobe::Sheen));
  EXPECT_TRUE(zero(1, Lobe::Clearcoat));
  const std::string text = formatComparison(c);
  EXPECT_NE(text.find("skipped, zero under both: sheen, clearcoat"), std::string::npos) << text;
  const auto j = nlohmann::json::parse(comparisonJson(c));
  EXPECT_EQ(j["materials"][1]["skipped_lobes"], nlohmann::json({"sheen", "clearcoat"}));
  EXPECT_EQ(j["materials"][0]["lobes"][0]["max_rel"], 0.0);

  CompareOptions bad = o;
  bad.gridSize = 1;
  EXPECT_THROW(compareProfiles(brdfcl::test::runtime(), materials, bad), Error);
  bad = o;
  bad.albedoViewDegrees = {90};
  EXPECT_THROW(compareProfiles(brdfcl::test::runtime(), materials, bad), Error);
}

// ---- the heat maps ----

TEST(CompareHeatMaps, FilesAreValidPngsOfTheFigureSize) {
  ScratchDir dir("compare-maps");
  auto materials = testMaterials();
  CompareOptions o;
  o.randomPairs = 100;
  Comparison c = compareProfiles(brdfcl::test::runtime(), materials, o);
  c.materials[1].index = 7;  // the file's index, as the CLI sets it
  for (const MaterialComparison& m : c.materials) {
    const std::vector<std::string> paths = writeRatioMaps(dir.dir(), c, m);
    ASSERT_EQ(paths.size(), 2u);
    const std::string stem = dir.dir() + "/" + (m.index == 0 ? "0_coated_velvet_spec_vs_spec" : "7_plain_plastic_spec_vs_spec");
    EXPECT_EQ(paths[0], stem + "_inplane.png");
    EXPECT_EQ(paths[1], stem + "_halfdiff.png");
    for (int k = 0; k < 2; ++k) {
      const plot::Figure f = drawRatioMap(c, m, k == 1);
      EXPECT_GE(f.panel.width, 360);  // 90 cells of 4 pixels
      EXPECT_EQ(f.panel.width, f.panel.height);
      const std::string png = brdfcl::test::slurp(paths[k]);
      ASSERT_GT(png.size(), 24u) << paths[k];
      EXPECT_EQ(png.substr(1, 3), "PNG");
      EXPECT_EQ(png.substr(12, 4), "IHDR");
      EXPECT_EQ(be32(png, 16), std::uint32_t(f.canvas.width()));
      EXPECT_EQ(be32(png, 20), std::uint32_t(f.canvas.height()));
      int w = 0, h = 0, n = 0;
      stbi_uc* px = stbi_load_from_memory(reinterpret_cast<const stbi_uc*>(png.data()), int(png.size()), &w, &h, &n, 3);
      ASSERT_NE(px, nullptr) << paths[k];
      EXPECT_EQ(w, f.canvas.width());
      EXPECT_EQ(h, f.canvas.height());
      std::set<std::uint32_t> colours;
      for (int i = 0; i < w * h; ++i) colours.insert(px[3 * i] << 16 | px[3 * i + 1] << 8 | px[3 * i + 2]);
      EXPECT_TRUE(std::equal(px, px + 3 * w * h, f.canvas.rgb().begin()));
      stbi_image_free(px);
      // Nothing but the field: no text, axes or colour bar, so a profile against itself is one colour.
      EXPECT_EQ(colours.size(), 1u);
      EXPECT_EQ(f.canvas.width(), f.panel.width);
      EXPECT_EQ(f.canvas.height(), f.panel.height);
      // A against itself: the whole panel is ratio 1, the diverging map's centre.
      const plot::Colour centre = plot::mapColour(plot::ColourMap::Diverging, 0.5);
      for (int y = 0; y < f.panel.height; y += 7)
        for (int x = 0; x < f.panel.width; x += 7) ASSERT_EQ(f.canvas.at(f.panel.x + x, f.panel.y + y), centre);
    }
  }
  for (const auto& name : dir.list()) EXPECT_EQ(name.find(".tmp."), std::string::npos) << name;
}

TEST(CompareHeatMaps, PanelFollowsTheLog2RatioField) {
  // A made-up field (the profiles still agree in this tree): log2 ratio rising with x, one NaN
  // cell. The panel must not be uniform, must be blue where A < B, red where A > B, magenta at NaN.
  Comparison c;
  c.options.gridSize = 90;
  c.options.a = Profile::Threejs;
  MaterialComparison m;
  m.name = "made up";
  m.floor = 1e-6;
  m.inPlaneLog2Ratio.resize(8100);
  for (int y = 0; y < 90; ++y)
    for (int x = 0; x < 90; ++x) m.inPlaneLog2Ratio[std::size_t(y) * 90 + x] = float((x - 44.5) / 44.5 * 3);
  m.inPlaneLog2Ratio[45 * 90 + 10] = kNaN;
  m.halfDiffLog2Ratio = m.inPlaneLog2Ratio;
  const plot::Figure f = drawRatioMap(c, m, false);
  if (const char* keep = std::getenv("BRDFCL_TEST_FIGURES")) plot::writePng(std::string(keep) + "/compare_ratio.png", f.canvas);
  const int s = f.panel.width / 90;
  auto cell = [&](int x, int y) { return f.canvas.at(f.panel.x + x * s + s / 2, f.panel.y + y * s + s / 2); };
  const plot::Colour left = cell(0, 0), right = cell(89, 0);
  EXPECT_NE(left, right);
  EXPECT_GT(left.b, left.r);    // A < B: blue
  EXPECT_GT(right.r, right.b);  // A > B: red
  EXPECT_EQ(cell(10, 45), plot::kNotFinite);
  std::set<std::uint32_t> colours;
  for (int y = 0; y < f.panel.height; ++y)
    for (int x = 0; x < f.panel.width; ++x) {
      const plot::Colour p = f.canvas.at(f.panel.x + x, f.panel.y + y);
      colours.insert(p.r << 16 | p.g << 8 | p.b);
    }
  EXPECT_GT(colours.size(), 40u);
  // The range is the next of 0.25 .. 8 above the largest |log2 ratio| (3 here): 4.
  EXPECT_EQ(cell(0, 0), plot::mapColour(plot::ColourMap::Diverging, (-3.0 / 4 + 1) / 2));
  EXPECT_EQ(compareFileStem(m, Profile::Threejs, Profile::Spec), "0_made_up_threejs_vs_spec");
}

// ---- the command ----

TEST(CompareCli, PrintsTheTableAndJsonAndWritesTheHeatMaps) {
  ScratchDir dir("compare-cli");
  std::ofstream(dir.path("m.json")) << kMaterialsJson;
  const RunResult t = cli(dir, {"compare", "--materials", "m.json", "--profile", "spec", "--pairs", "500"});
  ASSERT_EQ(t.status, 0) << t.describe();
  for (const char* text : {"A = spec against B = spec", "8100 in the incidence plane", "500 out of it", "[0] coated velvet",
                           "[1] plain/plastic", "max d", "skipped, zero under both: sheen, clearcoat",
                           "directional albedo (luminance)", "80 deg"})
    EXPECT_NE(t.out.find(text), std::string::npos) << text << "\n" << t.out;

  const RunResult j = cli(dir, {"compare", "--materials", "m.json", "--material", "1", "--profile", "spec", "--against",
                                "spec", "--pairs", "500", "--json", "--out", "maps/sub"});
  ASSERT_EQ(j.status, 0) << j.describe();
  const auto doc = nlohmann::json::parse(j.out);
  EXPECT_EQ(doc["profile"], "spec");
  EXPECT_EQ(doc["against"], "spec");
  EXPECT_EQ(doc["in_plane_samples"], 8100);
  EXPECT_EQ(doc["out_of_plane_samples"], 500);
  ASSERT_EQ(doc["materials"].size(), 1u);
  const auto& m = doc["materials"][0];
  EXPECT_EQ(m["index"], 1);
  EXPECT_EQ(m["name"], "plain/plastic");
  EXPECT_EQ(m["lobes"][0]["lobe"], "all");
  EXPECT_EQ(m["lobes"][0]["max_rel"], 0.0);
  EXPECT_EQ(m["lobes"][0]["albedo_a"].size(), 5u);
  ASSERT_EQ(m["heat_maps"].size(), 2u);
  EXPECT_EQ(m["heat_maps"][0], "maps/sub/1_plain_plastic_spec_vs_spec_inplane.png");
  for (const auto& p : m["heat_maps"]) EXPECT_TRUE(fs::is_regular_file(dir.path(p.get<std::string>()))) << p;
}

TEST(CompareCli, BadInputsExitTwoWithOneLine) {
  ScratchDir dir("compare-bad");
  std::ofstream(dir.path("m.json")) << kMaterialsJson;
  std::ofstream(dir.path("afile")) << "keep";
  expectOneLineError(cli(dir, {"compare", "--materials", "m.json", "--profile", "unreal"}),
                     "unknown --profile value 'unreal'; use spec, khronos, threejs, filament, babylon or materialx");
  expectOneLineError(cli(dir, {"compare", "--materials", "m.json", "--profile", "spec", "--against", "x"}),
                     "unknown --against value 'x'");
  expectOneLineError(cli(dir, {"compare", "--materials", "missing.json", "--profile", "spec"}), "missing.json");
  expectOneLineError(cli(dir, {"compare", "--profile", "spec"}), "--materials is required");
  expectOneLineError(cli(dir, {"compare", "--materials", "m.json"}), "--profile is required");
  expectOneLineError(cli(dir, {"compare", "--materials", "m.json", "--profile", "spec", "--out", "afile"}),
                     "--out 'afile': it exists and is not a directory");
  EXPECT_EQ(brdfcl::test::slurp(dir.path("afile")), "keep");
  expectOneLineError(cli(dir, {"compare", "--materials", "m.json", "--profile", "spec", "--material", "2"}),
                     "--material 2 is out of range: m.json has 2 material(s), 0 to 1");
  expectOneLineError(cli(dir, {"compare", "--materials", "m.json", "--profile", "spec", "--pairs", "-1"}),
                     "--pairs -1 is out of range");
  // Options are checked before the materials are read (this file does not exist).
  expectOneLineError(cli(dir, {"compare", "--materials", "none.json", "--profile", "bad"}), "--profile");
}
