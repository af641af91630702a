// The engine LUTs (brdfcl lut): every kind against a double-precision integral over L built here
// from the reference terms (an independent parameterization: the bake integrates over H), the
// split-sum closed forms, quadrature convergence, the three writers' round trips and the CLI errors.
#include <gtest/gtest.h>
#include <sys/wait.h>

#include <OpenEXR/ImfChannelList.h>
#include <OpenEXR/ImfFrameBuffer.h>
#include <OpenEXR/ImfHeader.h>
#include <OpenEXR/ImfInputFile.h>
#include <Imath/ImathBox.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <regex>
#include <sstream>

#include "brdfcl/error.hpp"
#include "brdfcl/lut.hpp"
#include "support.hpp"

using namespace brdfcl;
using namespace brdfcl::test;
namespace fs = std::filesystem;

namespace {

// Size 21 puts texels on multiples of 0.05 in N.V and roughness.
constexpr std::size_t kSize = 21;
const std::vector<std::size_t> kTexels = {1, 2, 4, 6, 10, 14, 18, 20};  // 0.05 .. 1

// integral over the upper hemisphere of L of g(L) (N.L) dw_L, N.V = nv, V in the XZ plane, by
// nested adaptive Gauss-Kronrod in (N.L, phi_L); `peaks` are extra N.L breaks where g is sharp.
double hemisphere(double nv, const std::function<double(const ref::Vec3&, const ref::Vec3&)>& g,
                  std::vector<double> peaks) {
  const ref::Vec3 V{std::sqrt(1 - nv * nv), 0, nv};
  auto inner = [&](double nl) {
    const double sl = std::sqrt(std::max(0.0, 1 - nl * nl));
    auto f = [&](double phi) {
      const ref::Vec3 L{sl * std::cos(phi), sl * std::sin(phi), nl};
      return g(L, V);
    };
    // Symmetric about phi = 0; the mirror direction is at phi = pi, an endpoint.
    return 2 * nl * (ref::integrate(f, 0, M_PI / 2, 1e-10, 20000) + ref::integrate(f, M_PI / 2, M_PI, 1e-10, 20000));
  };
  peaks.insert(peaks.end(), {0.0, 1.0});
  std::sort(peaks.begin(), peaks.end());
  double sum = 0;
  for (std::size_t k = 0; k + 1 < peaks.size(); ++k)
    if (peaks[k + 1] > peaks[k]) sum += ref::integrate(inner, peaks[k], peaks[k + 1], 1e-9, 20000);
  return sum;
}

ref::Vec3 halfVector(const ref::Vec3& L, const ref::Vec3& V) {
  ref::Vec3 h{L.x + V.x, L.y + V.y, L.z + V.z};
  const double n = std::sqrt(h.x * h.x + h.y * h.y + h.z * h.z);
  return {h.x / n, h.y / n, h.z / n};
}

// Split-sum GGX {A, B} at N.V = nv, alpha = r^2.
std::array<double, 2> ggxDfgReference(double nv, double r) {
  const double alpha = r * r;
  std::array<double, 2> out{};
  for (int c = 0; c < 2; ++c) {
    out[c] = hemisphere(
        nv,
        [&](const ref::Vec3& L, const ref::Vec3& V) {
          const auto H = halfVector(L, V);
          const double vh = V.x * H.x + V.y * H.y + V.z * H.z;
          const double w = std::pow(1 - vh, 5);
          const double dv = ref::D_GGX(H.z, alpha) * ref::V_SmithGGXCorrelated(L.z, V.z, alpha);
          return (c == 0 ? 1 - w : w) * dv;
        },
        // The lobe sits around the mirror direction N.L = N.V, about alpha wide.
        {std::max(0.0, nv - 8 * alpha), nv, std::min(1.0, nv + 8 * alpha)});
  }
  return out;
}

double charlieDfgReference(double nv, double r) {
  const double alpha = r * r;
  return hemisphere(
      nv,
      [&](const ref::Vec3& L, const ref::Vec3& V) {
        const auto H = halfVector(L, V);
        return ref::D_Charlie(H.z, alpha) * ref::V_Charlie(L.z, V.z, alpha);
      },
      // Small-alpha Charlie puts its mass at grazing N.L.
      {1e-4, 1e-3, 1e-2, 0.05, 0.2});
}

struct Worst {
  double err = 0;
  std::string where;
  void check(double got, double want, const std::string& what) {
    const double e = std::fabs(got - want);
    if (!(e <= err)) {
      err = std::isfinite(got) ? e : INFINITY;
      std::ostringstream o;
      o.precision(9);
      o << what << ": LUT " << got << ", reference " << want;
      where = o.str();
    }
  }
};

std::string texel(std::size_t i, std::size_t j) {
  return "N.V " + std::to_string(double(i) / (kSize - 1)) + ", roughness " + std::to_string(double(j) / (kSize - 1));
}

TEST(Lut, GgxDfgMatchesReferenceIntegral) {
  const auto lut = bakeLut(runtime(), LutKind::GgxDfg, kSize);
  ASSERT_EQ(lut.channels, 2);
  Worst worst;
  for (auto j : kTexels)
    for (auto i : kTexels) {
      const auto want = ggxDfgReference(double(i) / (kSize - 1), double(j) / (kSize - 1));
      worst.check(lut.at(i, j, 0), want[0], "A at " + texel(i, j));
      worst.check(lut.at(i, j, 1), want[1], "B at " + texel(i, j));
    }
  std::printf("ggx-dfg: max |LUT - reference| = %.3g over %zu texels\n", worst.err, kTexels.size() * kTexels.size());
  EXPECT_LE(worst.err, 1e-4) << "worst: " << worst.where;
}

TEST(Lut, CharlieDfgMatchesReferenceIntegral) {
  const auto lut = bakeLut(runtime(), LutKind::CharlieDfg, kSize);
  ASSERT_EQ(lut.channels, 1);
  Worst worst, table;
  for (auto j : kTexels)
    for (auto i : kTexels) {
      const double nv = double(i) / (kSize - 1), r = double(j) / (kSize - 1);
      const double want = charlieDfgReference(nv, r);
      worst.check(lut.at(i, j), want, "at " + texel(i, j));
      // The reference's own E integral of the same lobe agrees with the integral above.
      table.check(want, ref::sheenAlbedo(nv, r, SheenDistribution::Charlie, SheenVisibility::Charlie),
                  "ref::sheenAlbedo at " + texel(i, j));
    }
  std::printf("charlie-dfg: max |LUT - reference| = %.3g\n", worst.err);
  EXPECT_LE(worst.err, 1e-4) << "worst: " << worst.where;
  EXPECT_LE(table.err, 1e-5) << "worst: " << table.where;
}

TEST(Lut, SheenEMatchesReferenceAlbedoForEveryOption) {
  for (auto d : {SheenDistribution::Charlie, SheenDistribution::Ashikhmin})
    for (auto v : {SheenVisibility::Charlie, SheenVisibility::Ashikhmin}) {
      EvalOptions o;
      o.sheenDistribution = d;
      o.sheenVisibility = v;
      const auto lut = bakeLut(runtime(), LutKind::SheenE, kSize, o);
      EXPECT_EQ(lut.distribution, d);
      EXPECT_EQ(lut.visibility, v);
      Worst worst;
      for (auto j : kTexels)
        for (auto i : kTexels) {
          const double nv = double(i) / (kSize - 1), r = double(j) / (kSize - 1);
          worst.check(lut.at(i, j), ref::sheenAlbedo(nv, r, d, v), "at " + texel(i, j));
        }
      std::printf("sheen-e %s D, %s V: max |LUT - reference| = %.3g\n", toString(d), toString(v), worst.err);
      EXPECT_LE(worst.err, 1e-4) << toString(d) << " D, " << toString(v) << " V, worst: " << worst.where;
    }
}

// Split-sum facts: A + B is the albedo of the (F = 1) GGX lobe, so <= 1; it tends to 1 for a
// smooth surface seen head-on; there w = (1 - V.H)^5 ~ 0, so B is tiny.
TEST(Lut, GgxDfgClosedForms) {
  const std::size_t n = 64;
  const auto lut = bakeLut(runtime(), LutKind::GgxDfg, n);
  double maxSum = 0;
  for (std::size_t j = 0; j < n; ++j)
    for (std::size_t i = 0; i < n; ++i) {
      EXPECT_GE(lut.at(i, j, 0), 0.0f);
      EXPECT_GE(lut.at(i, j, 1), 0.0f);
      maxSum = std::max(maxSum, double(lut.at(i, j, 0)) + lut.at(i, j, 1));
    }
  EXPECT_LE(maxSum, 1.0 + 1e-4);
  const auto small = bakeLut(runtime(), LutKind::GgxDfg, kSize);
  EXPECT_NEAR(small.at(kSize - 1, 1, 0) + small.at(kSize - 1, 1, 1), 1.0, 1e-2);  // N.V = 1, roughness 0.05
  for (std::size_t j = 0; j < kSize; ++j) EXPECT_LT(small.at(kSize - 1, j, 1), 1e-3) << "roughness row " << j;
}

TEST(Lut, BakeQuadratureHasConverged) {
  for (auto kind : {LutKind::GgxDfg, LutKind::CharlieDfg}) {
    const auto a = bakeLut(runtime(), kind, 33, {}, 12);
    const auto b = bakeLut(runtime(), kind, 33, {}, 24);
    double worst = 0;
    std::size_t at = 0;
    for (std::size_t k = 0; k < a.values.size(); ++k) {
      const double e = std::fabs(a.values[k] - b.values[k]) / std::max(1.0, double(b.values[k]));
      if (e > worst) worst = e, at = k;
    }
    const std::size_t t = at / a.channels;
    std::printf("%s: 12 vs 24 nodes per panel differ by <= %.3g of max(1, value)\n", toString(kind), worst);
    EXPECT_LE(worst, 2e-5) << toString(kind) << " at texel (" << t % 33 << ", " << t / 33 << ") channel "
                           << at % a.channels << ": " << a.values[at] << " vs " << b.values[at];
  }
}

// docs/cli.md ("Look-up tables") says so: charlie-dfg is sheen-e at its defaults, and only the Ashikhmin
// options make sheen-e another table.
TEST(Lut, CharlieDfgIsSheenEAtItsDefaults) {
  const Lut charlie = bakeLut(runtime(), LutKind::CharlieDfg, 16);
  const Lut sheenE = bakeLut(runtime(), LutKind::SheenE, 16);
  EXPECT_EQ(charlie.values, sheenE.values);
  EvalOptions ashikhmin;
  ashikhmin.sheenVisibility = SheenVisibility::Ashikhmin;
  EXPECT_NE(bakeLut(runtime(), LutKind::SheenE, 16, ashikhmin).values, charlie.values);
}

TEST(Lut, SizeOutOfRangeIsAUserError) {
  for (std::size_t s : {std::size_t(0), std::size_t(1), std::size_t(4097)}) {
    try {
      bakeLut(runtime(), LutKind::GgxDfg, s);
      ADD_FAILURE() << "size " << s << " accepted";
    } catch (const brdfcl::Error& e) {
      EXPECT_EQ(e.exitCode(), 2);
    }
  }
}

// ---- Writers ----

class LutFiles : public testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() / ("brdfcl-lut-" + std::to_string(::getpid()));
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }
  std::string path(const std::string& name) const { return (dir_ / name).string(); }
  std::size_t entries() const { return std::distance(fs::directory_iterator(dir_), fs::directory_iterator()); }
  fs::path dir_;
};

Lut smallLut(LutKind kind) { return bakeLut(runtime(), kind, 5); }

TEST_F(LutFiles, ExrRoundTripsFloatChannels) {
  for (auto kind : {LutKind::GgxDfg, LutKind::CharlieDfg}) {
    const auto lut = smallLut(kind);
    const auto file = path("t.EXR");
    writeLut(lut, file);
    Imf::InputFile in(file.c_str());
    const auto dw = in.header().dataWindow();
    ASSERT_EQ(dw.max.x - dw.min.x + 1, 5);
    ASSERT_EQ(dw.max.y - dw.min.y + 1, 5);
    const char* names[] = {"R", "G"};
    int count = 0;
    for (auto it = in.header().channels().begin(); it != in.header().channels().end(); ++it) {
      EXPECT_EQ(it.channel().type, Imf::FLOAT);
      ++count;
    }
    ASSERT_EQ(count, lut.channels);
    std::vector<float> back(lut.values.size(), -1.0f);
    Imf::FrameBuffer fb;
    for (int c = 0; c < lut.channels; ++c)
      fb.insert(names[c], Imf::Slice(Imf::FLOAT, reinterpret_cast<char*>(back.data() + c), sizeof(float) * lut.channels,
                                      sizeof(float) * lut.channels * 5));
    in.setFrameBuffer(fb);
    in.readPixels(dw.min.y, dw.max.y);
    EXPECT_EQ(back, lut.values) << toString(kind);
  }
}

TEST_F(LutFiles, CsvRoundTrips) {
  const auto lut = smallLut(LutKind::GgxDfg);
  writeLut(lut, path("t.csv"));
  std::ifstream in(path("t.csv"));
  std::string line;
  std::getline(in, line);
  EXPECT_EQ(line, "nv,roughness,A,B");
  std::size_t row = 0;
  while (std::getline(in, line)) {
    float nv, r, a, b;
    ASSERT_EQ(std::sscanf(line.c_str(), "%f,%f,%f,%f", &nv, &r, &a, &b), 4) << line;
    const std::size_t i = row % 5, j = row / 5;
    EXPECT_FLOAT_EQ(nv, float(i) / 4);
    EXPECT_FLOAT_EQ(r, float(j) / 4);
    EXPECT_EQ(a, lut.at(i, j, 0));  // %.9g round-trips a float exactly
    EXPECT_EQ(b, lut.at(i, j, 1));
    ++row;
  }
  EXPECT_EQ(row, 25u);
}

TEST_F(LutFiles, HeaderHoldsTheArrayAndCompiles) {
  const auto lut = smallLut(LutKind::GgxDfg);
  const auto file = path("ggx.h");
  writeLut(lut, file);
  std::ifstream in(file);
  std::stringstream ss;
  ss << in.rdbuf();
  const std::string text = ss.str();
  EXPECT_NE(text.find("#define BRDFCL_GGX_DFG_LUT_SIZE 5"), std::string::npos);
  EXPECT_NE(text.find("#define BRDFCL_GGX_DFG_LUT_CHANNELS 2"), std::string::npos);
  const auto open = text.find("brdfcl_ggx_dfg_lut[");
  ASSERT_NE(open, std::string::npos);
  const auto body = text.substr(text.find('{', open) + 1, text.find("};", open) - text.find('{', open) - 1);
  std::vector<float> values;
  std::stringstream items(body);
  for (std::string item; std::getline(items, item, ',');) values.push_back(std::strtof(item.c_str(), nullptr));
  EXPECT_EQ(values, lut.values);
  // The array length must match the declared SIZE*SIZE*CHANNELS: a C compiler checks that.
  if (std::system("command -v cc >/dev/null 2>&1") == 0) {
    const auto src = path("use.c");
    std::ofstream(src) << "#include \"ggx.h\"\n_Static_assert(sizeof brdfcl_ggx_dfg_lut / sizeof(float) == "
                          "BRDFCL_GGX_DFG_LUT_SIZE * BRDFCL_GGX_DFG_LUT_SIZE * BRDFCL_GGX_DFG_LUT_CHANNELS, \"n\");\n"
                          "float first(void) { return brdfcl_ggx_dfg_lut[0]; }\n";
    const std::string cmd = "cc -std=c99 -Wall -Werror -c " + src + " -o " + path("use.o") + " 2>&1";
    EXPECT_EQ(std::system(cmd.c_str()), 0) << cmd;
  }
}

TEST_F(LutFiles, UnknownExtensionIsAUserErrorAndWritesNothing) {
  const auto lut = smallLut(LutKind::CharlieDfg);
  try {
    writeLut(lut, path("t.png"));
    ADD_FAILURE() << ".png accepted";
  } catch (const brdfcl::Error& e) {
    EXPECT_EQ(e.exitCode(), 2);
    EXPECT_NE(std::string(e.what()).find("t.png"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find(".exr, .csv, .h or .npy"), std::string::npos) << e.what();
  }
  EXPECT_EQ(entries(), 0u);
}

// ---- CLI ----

int runCli(const std::string& args, const std::string& errFile) {
  const std::string cmd = std::string(BRDFCL_CLI_PATH) + " " + args + " >/dev/null 2>" + errFile;
  const int rc = std::system(cmd.c_str());
  return WIFEXITED(rc) ? WEXITSTATUS(rc) : -1;
}

TEST_F(LutFiles, CliBadArgumentsExitTwoWithNoOutput) {
  const auto err = (fs::temp_directory_path() / ("brdfcl-lut-err-" + std::to_string(::getpid()))).string();
  const std::vector<std::pair<std::string, std::string>> cases = {
      {"--kind ggx --out " + path("a.csv"), "unknown --kind value 'ggx'"},
      {"--kind ggx-dfg --size 1 --out " + path("a.csv"), "--size 1 is out of range"},
      {"--kind ggx-dfg --size 4097 --out " + path("a.csv"), "--size 4097 is out of range"},
      {"--kind ggx-dfg --size x --out " + path("a.csv"), "--size"},
      {"--kind charlie-dfg --out " + path("a.png"), "use .exr, .csv, .h or .npy"},
      {"--kind sheen-e --sheen-visibility foo --out " + path("a.exr"), "--sheen-visibility"},
  };
  for (const auto& [args, message] : cases) {
    EXPECT_EQ(runCli("lut " + args, err), 2) << args;
    std::ifstream in(err);
    std::string line;
    std::getline(in, line);
    EXPECT_NE(line.find(message), std::string::npos) << args << " -> " << line;
    EXPECT_EQ(entries(), 0u) << args;
  }
  fs::remove(err);
}

TEST_F(LutFiles, CliWritesEachFormat) {
  const auto err = (fs::temp_directory_path() / ("brdfcl-lut-err-" + std::to_string(::getpid()))).string();
  for (const char* name : {"s.exr", "s.csv", "s.h"}) {
    EXPECT_EQ(runCli(std::string("lut --kind sheen-e --size 8 --sheen-distribution ashikhmin --out ") + path(name), err),
              0)
        << name;
    EXPECT_TRUE(fs::is_regular_file(path(name))) << name;
  }
  EXPECT_EQ(entries(), 3u);  // no temporaries left behind
  fs::remove(err);
}

}  // namespace
