// End-to-end tests of the brdfcl command line: the built binary (BRDFCL_CLI_PATH) is run as a user
// would run it, and its files, exit status and stderr are checked against the eval contract
// (CSV/NPY in and out, --grid, options, one-line errors with nothing left behind, devices).
#include <fcntl.h>
#include <gtest/gtest.h>
#include <signal.h>
#include <spawn.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <array>
#include <atomic>
#include <cerrno>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <map>
#include <random>
#include <regex>
#include <set>
#include <sstream>
#include <stdexcept>
#include <string>
#include <thread>
#include <vector>

#include "npy.hpp"
#include "process.hpp"
#include "support.hpp"

namespace fs = std::filesystem;
using namespace brdfcl;

namespace {

// ---------------------------------------------------------------------------------------------
// Running the binary

using brdfcl::test::RunResult;

std::string readFile(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  if (!in) throw std::runtime_error("cannot read " + p.string());
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

void writeFile(const fs::path& p, const std::string& content) {
  std::ofstream out(p, std::ios::binary);
  out << content;
  if (!out) throw std::runtime_error("cannot write " + p.string());
}

std::atomic<int> dirCounter{0};

// ---------------------------------------------------------------------------------------------
// Test data. Direction components are multiples of 1/256 (or exact powers of two apart), so the
// CSV text, float32 and float64 hold exactly the same numbers and every input format must give
// bit-identical directions to the tool.

using Dir = std::array<double, 3>;
struct Sample {
  std::uint32_t material;
  Dir L, V;
};

bool belowHorizon(const Sample& s) { return s.L[2] <= 0.0 || s.V[2] <= 0.0; }

Dir quantized(const std::array<float, 3>& unit, double scale) {
  Dir d;
  for (int c = 0; c < 3; ++c) d[c] = std::round(unit[c] * scale * 256.0) / 256.0;
  return d;
}

std::vector<Sample> standardSamples() {
  std::mt19937_64 rng(test::seed() ^ 0xc11u);
  std::uniform_real_distribution<double> scale(0.5, 4.0);
  std::vector<Sample> s;
  // Hand-picked first, so the grid test (which uses a prefix) sees the special cases too.
  s.push_back({0, {0, 0, 1}, {0, 0.5, 1}});
  s.push_back({1, {0, 0, -1}, {0, 0, 1}});                         // light below
  s.push_back({2, {0.25, 0.5, 1}, {0.5, -0.25, -0.0078125}});      // viewer just below
  s.push_back({1, {1, 0, 0}, {0, 0.75, 0.5}});                     // light at the horizon: N.L = 0
  s.push_back({1, {3145728, 0, 4194304}, {0.0009765625, 0, 0.001953125}});  // huge and tiny lengths
  s.push_back({2, {-3, 4, 12}, {7, -2, 5}});
  s.push_back({0, {0.5, 0.5, -0.25}, {0.25, 0.25, -0.5}});         // both below
  s.push_back({2, {0, 0, 1}, {0, 0, 1}});                          // normal incidence, L = V
  for (std::uint32_t i = 0; s.size() < 52; ++i) {
    const bool below = i % 9 == 4;
    const auto L = test::randomDirection(rng, 0.05f, below && i % 2 == 0);
    const auto V = test::randomDirection(rng, 0.05f, below && i % 2 == 1);
    s.push_back({i % 3, quantized(L, scale(rng)), quantized(V, scale(rng))});
  }
  return s;
}

std::string num(double x) {
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.17g", x);  // exact for the dyadic values used here
  return buf;
}

std::string samplesCsv(const std::vector<Sample>& samples, bool withMaterial = true) {
  std::string t = withMaterial ? "material,Lx,Ly,Lz,Vx,Vy,Vz\n" : "Lx,Ly,Lz,Vx,Vy,Vz\n";
  for (const auto& s : samples) {
    if (withMaterial) t += std::to_string(s.material) + ",";
    t += num(s.L[0]) + "," + num(s.L[1]) + "," + num(s.L[2]) + "," + num(s.V[0]) + "," + num(s.V[1]) + "," +
         num(s.V[2]) + "\n";
  }
  return t;
}

std::string samplesNpy(const std::vector<Sample>& samples, bool float32, bool withMaterial = true) {
  std::vector<double> v;
  for (const auto& s : samples) {
    if (withMaterial) v.push_back(s.material);
    v.insert(v.end(), s.L.begin(), s.L.end());
    v.insert(v.end(), s.V.begin(), s.V.end());
  }
  return brdfcl::test::npyArray(v, withMaterial ? 7 : 6, float32);
}

// The glTF document and the parameters it must produce. Only the draft material leaves keys to
// the defaults whose values stay in the clamp-free domain (baseColorFactor, colorFactor).
const char* kGltf = R"({
  "asset": {"version": "2.0", "generator": "brdfcl test_cli"},
  "extensionsUsed": ["KHR_materials_sheen", "KHR_materials_clearcoat", "KHR_materials_anisotropy"],
  "materials": [
    {
      "name": "plain",
      "pbrMetallicRoughness": {"baseColorFactor": [0.8, 0.35, 0.1, 1.0], "metallicFactor": 0.0,
                               "roughnessFactor": 0.45}
    },
    {
      "name": "coated velvet",
      "pbrMetallicRoughness": {"baseColorFactor": [0.3, 0.5, 0.7, 0.5], "metallicFactor": 0.25,
                               "roughnessFactor": 0.6},
      "extensions": {
        "KHR_materials_sheen": {"sheenColorFactor": [0.6, 0.4, 0.5], "sheenRoughnessFactor": 0.35},
        "KHR_materials_clearcoat": {"clearcoatFactor": 0.7, "clearcoatRoughnessFactor": 0.2},
        "KHR_materials_anisotropy": {"anisotropyStrength": 0.6, "anisotropyRotation": 0.9}
      }
    },
    {
      "name": "draft sheen",
      "pbrMetallicRoughness": {"metallicFactor": 0.1, "roughnessFactor": 0.55},
      "extensions": {"KHR_materials_sheen": {"intensityFactor": 0.8}}
    }
  ]
})";

std::vector<MaterialParams> gltfMaterials() {
  std::vector<MaterialParams> m(3);
  // Assigning the double literals rounds them as the tool does (JSON double -> float).
  m[0].name = "plain";
  m[0].baseColor = {float(0.8), float(0.35), float(0.1)};
  m[0].metallic = float(0.0);
  m[0].roughness = float(0.45);

  m[1].name = "coated velvet";
  m[1].baseColor = {float(0.3), float(0.5), float(0.7)};
  m[1].metallic = float(0.25);
  m[1].roughness = float(0.6);
  m[1].sheenColor = {float(0.6), float(0.4), float(0.5)};
  m[1].sheenRoughness = float(0.35);
  m[1].clearcoat = float(0.7);
  m[1].clearcoatRoughness = float(0.2);
  m[1].anisotropyStrength = float(0.6);
  m[1].anisotropyRotation = float(0.9);

  m[2].name = "draft sheen";
  m[2].metallic = float(0.1);
  m[2].roughness = float(0.55);
  m[2].draftSheen = true;
  m[2].draftIntensity = float(0.8);
  return m;
}

// ---------------------------------------------------------------------------------------------
// Reading the tool's output

struct CsvResult {
  std::vector<std::string> text;  // 3 per row, as written
  std::vector<double> values;
};

CsvResult readCsvResult(const fs::path& p) {
  std::istringstream in(readFile(p));
  std::string line;
  if (!std::getline(in, line) || line != "r,g,b") throw std::runtime_error(p.string() + ": header is '" + line + "'");
  CsvResult r;
  for (std::size_t n = 2; std::getline(in, line); ++n) {
    std::size_t start = 0;
    for (int c = 0; c < 3; ++c) {
      const std::size_t comma = line.find(',', start);
      if ((c < 2) == (comma == std::string::npos))
        throw std::runtime_error(p.string() + ":" + std::to_string(n) + ": not 3 fields: '" + line + "'");
      const std::string field = line.substr(start, c < 2 ? comma - start : std::string::npos);
      char* end = nullptr;
      const double v = std::strtod(field.c_str(), &end);
      if (field.empty() || *end != '\0')
        throw std::runtime_error(p.string() + ":" + std::to_string(n) + ": not a number: '" + field + "'");
      r.text.push_back(field);
      r.values.push_back(v);
      start = comma + 1;
    }
  }
  return r;
}

std::vector<double> readNpyResult(const fs::path& p) {
  const std::string b = readFile(p);
  if (b.size() < 10 || b.compare(0, 6, "\x93NUMPY") != 0) throw std::runtime_error(p.string() + ": no NPY magic");
  if (b[6] != 1 || b[7] != 0) throw std::runtime_error(p.string() + ": not NPY version 1.0");
  const std::size_t hlen = static_cast<unsigned char>(b[8]) | static_cast<std::size_t>(static_cast<unsigned char>(b[9])) << 8;
  if ((10 + hlen) % 64 != 0 || b.size() < 10 + hlen) throw std::runtime_error(p.string() + ": bad header length");
  const std::string h = b.substr(10, hlen);
  std::smatch m;
  if (h.find("'descr': '<f4'") == std::string::npos || h.find("'fortran_order': False") == std::string::npos ||
      !std::regex_search(h, m, std::regex(R"('shape': \((\d+), 3\))")) || h.back() != '\n')
    throw std::runtime_error(p.string() + ": unexpected header " + h);
  const std::size_t rows = std::stoul(m[1]);
  if (b.size() != 10 + hlen + rows * 12)
    throw std::runtime_error(p.string() + ": " + std::to_string(b.size()) + " bytes for " + std::to_string(rows) +
                             " rows");
  std::vector<double> out(3 * rows);
  for (std::size_t i = 0; i < out.size(); ++i) {
    float f;
    std::memcpy(&f, b.data() + 10 + hlen + 4 * i, 4);
    out[i] = f;
  }
  return out;
}

// %.9g drops trailing zeros, so "0.12345678" is a 9-digit rendering when the float it denotes,
// printed to 9 digits, is that same number; a tool printing %.6g fails this for almost all values.
bool hasNineSignificantDigits(const std::string& text) {
  int digits = 0;
  bool leading = true;
  for (char c : text) {
    if (c == 'e' || c == 'E') break;
    if (c < '0' || c > '9') continue;
    if (c != '0') leading = false;
    if (!leading) ++digits;
  }
  if (digits >= 9) return true;
  const double x = std::strtod(text.c_str(), nullptr);
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.8e", static_cast<double>(static_cast<float>(x)));
  return std::strtod(buf, nullptr) == x;
}

ref::Vec3 normalizedFloat(const Dir& d) {
  const double len = std::sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
  return {double(float(d[0] / len)), double(float(d[1] / len)), double(float(d[2] / len))};
}

// Relative to the value itself: the sheen colors are moderate, so the albedo scaling never
// amplifies the table's error past 1e-3 (test_accuracy covers the extreme colors).
void expectMatchesReference(const std::vector<double>& got, const std::vector<MaterialParams>& materials,
                            const std::vector<Sample>& samples, const EvalOptions& o, double rel = 1e-3,
                            double abs = 1e-6) {
  ASSERT_EQ(got.size(), 3 * samples.size());
  test::WorstCase w;
  for (std::size_t i = 0; i < samples.size(); ++i) {
    const auto& s = samples[i];
    const auto& m = materials[s.material];
    const auto want = ref::brdf(m, o, normalizedFloat(s.L), normalizedFloat(s.V));
    for (int c = 0; c < 3; ++c)
      w.check(got[3 * i + c], want[c], std::fabs(want[c]), rel, abs, [&] {
        return "sample " + std::to_string(i) + " channel " + std::to_string(c) + ", material " + test::describe(m) +
               "; " + test::describeOptions(o);
      });
  }
  EXPECT_LE(w.worstRatio, 1.0) << "worst: " << w.report;
}

// Equal within `rel` (relative) or `abs`, element by element.
void expectClose(const std::vector<double>& a, const std::vector<double>& b, double rel, double abs,
                 const std::string& what) {
  ASSERT_EQ(a.size(), b.size()) << what;
  std::size_t bad = 0, first = 0;
  for (std::size_t i = 0; i < a.size(); ++i)
    if (!(std::fabs(a[i] - b[i]) <= rel * std::fabs(b[i]) + abs) && bad++ == 0) first = i;
  EXPECT_EQ(bad, 0u) << what << ": first difference at row " << first / 3 << " channel " << first % 3 << ": "
                     << a[first] << " vs " << b[first];
}

// ---------------------------------------------------------------------------------------------

class Cli : public ::testing::Test {
 protected:
  void SetUp() override {
    const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
    root_ = fs::temp_directory_path() /
            ("brdfcl-cli-" + std::to_string(::getpid()) + "-" + info->name() + "-" + std::to_string(dirCounter++));
    fs::remove_all(root_);
    work_ = root_ / "work";
    fs::create_directories(work_);
  }
  void TearDown() override {
    std::error_code ec;
    fs::remove_all(root_, ec);
  }

  // Files the tool reads and writes live in work_; its captured stdout/stderr stay outside, so
  // listing work_ shows exactly what the tool left behind.
  std::string path(const std::string& name) const { return (work_ / name).string(); }
  std::string write(const std::string& name, const std::string& content) const {
    writeFile(work_ / name, content);
    return path(name);
  }
  std::set<std::string> listWork() const {
    std::set<std::string> names;
    for (const auto& e : fs::recursive_directory_iterator(work_)) names.insert(fs::relative(e.path(), work_).string());
    return names;
  }

  RunResult run(const std::vector<std::string>& args, const std::string& cwd = "") const {
    std::vector<std::string> argv{BRDFCL_CLI_PATH};
    argv.insert(argv.end(), args.begin(), args.end());
    return brdfcl::test::runProcess(argv, root_.string(), cwd);
  }

  RunResult eval(const std::string& materials, const std::string& samples, const std::string& out,
                 const std::vector<std::string>& extra = {}) const {
    std::vector<std::string> args{"eval", "--materials", materials, "--samples", samples, "--out", out};
    args.insert(args.end(), extra.begin(), extra.end());
    return run(args);
  }

  // Runs eval (which must succeed) and returns the NPY result.
  std::vector<double> evalNpy(const std::string& materials, const std::string& samples,
                              const std::vector<std::string>& extra = {}, const std::string& outName = "o.npy") {
    const RunResult r = eval(materials, samples, path(outName), extra);
    EXPECT_EQ(r.status, 0) << r.describe();
    EXPECT_TRUE(r.err.empty()) << r.err;
    if (r.status != 0) return {};
    auto v = readNpyResult(path(outName));
    fs::remove(path(outName));
    return v;
  }

  // The error contract: exit 2, nothing on stdout, one line "brdfcl: ..." holding every needle.
  static void expectUserError(const RunResult& r, const std::vector<std::string>& needles) {
    EXPECT_EQ(r.status, 2) << r.describe();
    EXPECT_TRUE(r.out.empty()) << r.describe();
    const auto lines = r.errorLines();
    ASSERT_EQ(lines.size(), 1u) << r.describe();
    EXPECT_EQ(lines[0].rfind("brdfcl: ", 0), 0u) << lines[0];
    EXPECT_FALSE(r.err.empty() || r.err.back() != '\n') << "stderr does not end with a newline: " << r.err;
    for (const auto& n : needles) EXPECT_NE(lines[0].find(n), std::string::npos) << "'" << lines[0] << "' lacks '" << n << "'";
  }

  fs::path root_, work_;
};

// ---------------------------------------------------------------------------------------------
// 1. Happy path

TEST_F(Cli, CsvMatchesReference) {
  const auto samples = standardSamples();
  const std::string m = write("scene.gltf", kGltf), s = write("s.csv", samplesCsv(samples));
  const RunResult r = eval(m, s, path("o.csv"));
  ASSERT_EQ(r.status, 0) << r.describe();
  EXPECT_TRUE(r.err.empty()) << r.err;
  EXPECT_EQ(listWork(), (std::set<std::string>{"scene.gltf", "s.csv", "o.csv"}));

  const CsvResult out = readCsvResult(path("o.csv"));
  ASSERT_EQ(out.values.size(), 3 * samples.size());
  expectMatchesReference(out.values, gltfMaterials(), samples, EvalOptions{});

  std::size_t below = 0, nonZero = 0;
  for (std::size_t i = 0; i < samples.size(); ++i) {
    for (int c = 0; c < 3; ++c) {
      const std::string& t = out.text[3 * i + c];
      if (belowHorizon(samples[i])) {
        EXPECT_EQ(out.values[3 * i + c], 0.0) << "row " << i << " is below the horizon but gives " << t;
      } else {
        EXPECT_GT(out.values[3 * i + c], 0.0) << "row " << i << ": " << t;
        EXPECT_TRUE(hasNineSignificantDigits(t)) << "row " << i << ": '" << t << "' has fewer than 9 digits";
        ++nonZero;
      }
    }
    below += belowHorizon(samples[i]);
  }
  // The fixture must exercise both kinds of rows, or the checks above prove little.
  EXPECT_GE(below, 6u);
  EXPECT_GE(nonZero, 3 * 40u);
}

// 2. NPY in either precision and NPY out give what the CSV run gives.
TEST_F(Cli, NpyInputsAndOutputMatchCsv) {
  const auto samples = standardSamples();
  const std::string m = write("m.json", kGltf);
  const std::string csv = write("s.csv", samplesCsv(samples));
  const std::string f32 = write("s32.npy", samplesNpy(samples, true));
  const std::string f64 = write("s64.NPY", samplesNpy(samples, false));

  RunResult r = eval(m, csv, path("o.csv"));
  ASSERT_EQ(r.status, 0) << r.describe();
  const auto csvOut = readCsvResult(path("o.csv")).values;
  ASSERT_EQ(csvOut.size(), 3 * samples.size());

  r = eval(m, f64, path("o64.csv"));
  ASSERT_EQ(r.status, 0) << r.describe();
  EXPECT_EQ(readFile(path("o64.csv")), readFile(path("o.csv"))) << "float64 NPY input changes the CSV output";

  const auto fromCsv = evalNpy(m, csv);
  const auto from32 = evalNpy(m, f32);
  const auto from64 = evalNpy(m, f64, {}, "o.NPY");
  expectClose(fromCsv, csvOut, 1e-6, 0.0, "NPY output vs CSV output");
  // The inputs hold identical numbers, so the directions and hence the results are identical.
  EXPECT_EQ(from32, fromCsv);
  EXPECT_EQ(from64, fromCsv);
}

// 3. --grid: every material x every direction, material-major, with or without a material column.
TEST_F(Cli, GridIsMaterialMajorProduct) {
  const auto all = standardSamples();
  const std::vector<Sample> dirs(all.begin(), all.begin() + 14);
  const auto materials = gltfMaterials();
  const std::string m = write("m.json", kGltf);

  std::vector<Sample> expanded;
  for (std::uint32_t k = 0; k < materials.size(); ++k)
    for (const auto& d : dirs) expanded.push_back({k, d.L, d.V});
  const auto perSample = evalNpy(m, write("expanded.csv", samplesCsv(expanded)));
  ASSERT_EQ(perSample.size(), 3 * materials.size() * dirs.size());
  expectMatchesReference(perSample, materials, expanded, EvalOptions{});

  const std::vector<std::pair<std::string, std::string>> inputs = {
      {"g7.csv", samplesCsv(dirs, true)},
      {"g6.csv", samplesCsv(dirs, false)},
      {"g6.npy", samplesNpy(dirs, true, false)},
      {"g7.npy", samplesNpy(dirs, false, true)},
  };
  for (const auto& [name, content] : inputs) {
    SCOPED_TRACE(name);
    const auto grid = evalNpy(m, write(name, content), {"--grid"});
    expectClose(grid, perSample, 1e-6, 1e-30, "--grid vs per-sample evaluation");
  }

  // CSV output of the grid too: the row count is materials x directions.
  const RunResult r = eval(m, path("g6.csv"), path("grid.csv"), {"--grid"});
  ASSERT_EQ(r.status, 0) << r.describe();
  expectClose(readCsvResult(path("grid.csv")).values, perSample, 2e-7, 0.0, "--grid CSV output");
}

// 4. Every option value selects its variant.
TEST_F(Cli, OptionValuesSelectTheirVariant) {
  const auto samples = standardSamples();
  const auto materials = gltfMaterials();
  const std::string m = write("m.json", kGltf), s = write("s.csv", samplesCsv(samples));

  const auto defaults = evalNpy(m, s);
  const auto explicitDefaults = evalNpy(m, s,
                                        {"--sheen-visibility", "charlie", "--sheen-distribution", "charlie",
                                         "--sheen-scaling", "min", "--lobe", "all"});
  EXPECT_EQ(explicitDefaults, defaults);

  struct Variant {
    std::vector<std::string> args;
    EvalOptions options;
  };
  EvalOptions o;
  std::vector<Variant> variants;
  o = {};
  o.sheenVisibility = SheenVisibility::Ashikhmin;
  variants.push_back({{"--sheen-visibility", "ashikhmin"}, o});
  o = {};
  o.sheenDistribution = SheenDistribution::Ashikhmin;
  variants.push_back({{"--sheen-distribution", "ashikhmin"}, o});
  o = {};
  o.sheenScaling = SheenScaling::View;
  variants.push_back({{"--sheen-scaling", "view"}, o});
  o = {};
  o.sheenScaling = SheenScaling::None;
  variants.push_back({{"--sheen-scaling", "none"}, o});
  const std::pair<const char*, Lobe> lobes[] = {
      {"diffuse", Lobe::Diffuse}, {"specular", Lobe::Specular}, {"sheen", Lobe::Sheen}, {"clearcoat", Lobe::Clearcoat}};
  for (const auto& [name, lobe] : lobes) {
    o = {};
    o.lobe = lobe;
    variants.push_back({{"--lobe", name}, o});
  }

  std::map<std::string, std::vector<double>> results;
  for (const auto& v : variants) {
    const std::string label = v.args[0] + " " + v.args[1];
    SCOPED_TRACE(label);
    results[label] = evalNpy(m, s, v.args);
    expectMatchesReference(results[label], materials, samples, v.options);
  }

  // The lobes partition the sum.
  std::vector<double> sum(defaults.size(), 0.0);
  for (const auto& [name, lobe] : lobes) {
    const auto& part = results[std::string("--lobe ") + name];
    ASSERT_EQ(part.size(), sum.size());
    for (std::size_t i = 0; i < sum.size(); ++i) sum[i] += part[i];
  }
  expectClose(sum, defaults, 1e-4, 1e-6, "sum of --lobe diffuse/specular/sheen/clearcoat vs all");

  // Facts that hold whatever the formulas, so a wrong option mapping fails even if the reference
  // shared the mistake: the sheen options change the ratified sheen material but not the one
  // without sheen, and only material 1 has a clearcoat lobe.
  const auto differsOn = [&](const std::vector<double>& a, const std::vector<double>& b, std::uint32_t material) {
    for (std::size_t i = 0; i < samples.size(); ++i)
      if (samples[i].material == material && !belowHorizon(samples[i]))
        for (int c = 0; c < 3; ++c)
          if (std::fabs(a[3 * i + c] - b[3 * i + c]) > 1e-4 * std::fabs(b[3 * i + c])) return true;
    return false;
  };
  const auto equalOn = [&](const std::vector<double>& a, const std::vector<double>& b, std::uint32_t material) {
    for (std::size_t i = 0; i < samples.size(); ++i)
      if (samples[i].material == material)
        for (int c = 0; c < 3; ++c)
          if (std::fabs(a[3 * i + c] - b[3 * i + c]) > 1e-6 * std::fabs(b[3 * i + c])) return false;
    return true;
  };
  for (const char* label : {"--sheen-visibility ashikhmin", "--sheen-distribution ashikhmin", "--sheen-scaling view",
                            "--sheen-scaling none"}) {
    SCOPED_TRACE(label);
    EXPECT_TRUE(differsOn(results[label], defaults, 1)) << "no effect on the ratified sheen material";
    EXPECT_TRUE(equalOn(results[label], defaults, 0)) << "changes the material without sheen";
  }
  for (std::uint32_t k : {0u, 2u}) {
    EXPECT_TRUE(equalOn(results["--lobe clearcoat"], std::vector<double>(defaults.size(), 0.0), k));
    EXPECT_TRUE(differsOn(results["--lobe diffuse"], defaults, k));
  }
  EXPECT_TRUE(equalOn(results["--lobe sheen"], std::vector<double>(defaults.size(), 0.0), 0));
  EXPECT_TRUE(differsOn(results["--lobe clearcoat"], std::vector<double>(defaults.size(), 0.0), 1));
}

TEST_F(Cli, UnknownOptionsAndValuesAreUserErrors) {
  const std::string m = write("m.json", kGltf), s = write("s.csv", samplesCsv(standardSamples()));
  const std::string out = path("o.csv");
  const std::vector<std::pair<std::vector<std::string>, std::string>> cases = {
      {{"--lobe", "foo"}, "--lobe"},
      {{"--sheen-scaling", "bar"}, "--sheen-scaling"},
      {{"--sheen-visibility", "velvet"}, "--sheen-visibility"},
      {{"--sheen-distribution", "ggx"}, "--sheen-distribution"},
      {{"--lobe", "Diffuse"}, "--lobe"},  // spellings are exact
      {{"--frobnicate"}, "--frobnicate"},
      {{"--lobe"}, "--lobe"},  // value missing
  };
  for (const auto& [args, needle] : cases) {
    SCOPED_TRACE(args[0] + (args.size() > 1 ? " " + args[1] : ""));
    std::vector<std::string> needles{needle};
    if (args.size() > 1) needles.push_back("'" + args[1] + "'");  // the rejected value too
    expectUserError(eval(m, s, out, args), needles);
    EXPECT_FALSE(fs::exists(out));
  }
  expectUserError(run({"eval", "--materials", m, "--samples", s}), {"--out"});
  expectUserError(run({"frobnicate"}), {"frobnicate"});  // an unknown subcommand
  EXPECT_EQ(listWork(), (std::set<std::string>{"m.json", "s.csv"}));
}

// ---------------------------------------------------------------------------------------------
// 5. Bad input: one line naming the file and place, exit 2, no output and no temporaries.

struct BadCase {
  std::string what;
  std::vector<std::pair<std::string, std::string>> files;  // name, content
  std::string materials = "m.json", samples = "s.csv", out = "o.csv";
  std::vector<std::string> extra;
  std::vector<std::string> needles;  // the file name and where in it
};

std::string csvWithRow(const std::string& row, std::size_t at) {
  // `row` becomes file line `at` (the header is line 1) among valid rows.
  std::string t = "material,Lx,Ly,Lz,Vx,Vy,Vz\n";
  for (std::size_t line = 2; line <= 6; ++line) t += line == at ? row + "\n" : "1,0.25,0.5,1,0,0.125,1\n";
  return t;
}

std::string npyWithRow(const std::vector<double>& row, std::size_t at, bool float32) {
  std::vector<double> v;
  for (std::size_t i = 0; i < 4; ++i) {
    const std::vector<double> good{2, 0.25, 0.5, 1, 0, 0.125, 1};
    const auto& r = i == at ? row : good;
    v.insert(v.end(), r.begin(), r.end());
  }
  return brdfcl::test::npyArray(v, 7, float32);
}

std::string gltfWith(const std::string& secondMaterial) {
  return "{\n  \"asset\": {\"version\": \"2.0\"},\n  \"materials\": [\n    {\"name\": \"ok\"},\n    " + secondMaterial +
         "\n  ]\n}\n";
}

// Each bad input eval refuses, with the words its one-line error must hold.
std::vector<BadCase> badInputCases() {
  const double nan = std::nan(""), inf = INFINITY;
  return {
      // Files that cannot be read.
      {"missing materials", {}, "absent.json", "s.csv", "o.csv", {}, {"absent.json", "No such file"}},
      {"materials is a directory", {}, "adir", "s.csv", "o.csv", {}, {"adir"}},
      {"missing samples", {}, "m.json", "absent.csv", "o.csv", {}, {"absent.csv", "No such file"}},
      {"samples is a directory", {}, "m.json", "adir", "o.csv", {}, {"adir"}},
      // Materials JSON.
      {"malformed JSON", {{"broken.json", gltfWith("{\"name\": \"x\",, }")}}, "broken.json", "s.csv", "o.csv", {},
       {"broken.json", "line 5"}},
      {"NaN literal", {{"nan.json", gltfWith("{\"pbrMetallicRoughness\": {\"roughnessFactor\": NaN}}")}}, "nan.json",
       "s.csv", "o.csv", {}, {"nan.json", "line 5"}},
      {"overflowing number",
       {{"inf.json", gltfWith("{\"pbrMetallicRoughness\": {\n      \"roughnessFactor\": 1e999}}")}}, "inf.json",
       "s.csv", "o.csv", {}, {"inf.json", "line 6"}},
      {"wrong type",
       {{"type.json", gltfWith("{\"pbrMetallicRoughness\": {\"metallicFactor\": \"0.5\"}}")}}, "type.json", "s.csv",
       "o.csv", {}, {"type.json", "materials[1].pbrMetallicRoughness.metallicFactor"}},
      {"out of range",
       {{"range.json", gltfWith("{\"extensions\": {\"KHR_materials_clearcoat\": {\"clearcoatFactor\": 1.5}}}")}},
       "range.json", "s.csv", "o.csv", {},
       {"range.json", "materials[1].extensions.KHR_materials_clearcoat.clearcoatFactor"}},
      {"short color",
       {{"color.json", gltfWith("{\"extensions\": {\"KHR_materials_sheen\": {\"sheenColorFactor\": [1, 0]}}}")}},
       "color.json", "s.csv", "o.csv", {}, {"color.json", "sheenColorFactor"}},
      {"materials not an array", {{"obj.json", "{\"materials\": {\"name\": \"x\"}}"}}, "obj.json", "s.csv", "o.csv", {},
       {"obj.json", "materials"}},
      {"no materials", {{"none.json", "{\"asset\": {\"version\": \"2.0\"}}"}}, "none.json", "s.csv", "o.csv", {},
       {"none.json", "materials"}},
      // Samples CSV.
      {"short row", {{"short.csv", csvWithRow("1,0.25,0.5,1,0,0.125", 3)}}, "m.json", "short.csv", "o.csv", {},
       {"short.csv:3:"}},
      {"non-numeric field", {{"text.csv", csvWithRow("1,0.25,abc,1,0,0.125,1", 4)}}, "m.json", "text.csv", "o.csv", {},
       {"text.csv:4:"}},
      {"empty field", {{"empty.csv", csvWithRow("1,0.25,,1,0,0.125,1", 2)}}, "m.json", "empty.csv", "o.csv", {},
       {"empty.csv:2:"}},
      {"NaN field", {{"nan.csv", csvWithRow("1,nan,0.5,1,0,0.125,1", 5)}}, "m.json", "nan.csv", "o.csv", {},
       {"nan.csv:5:"}},
      {"Inf field", {{"inf.csv", csvWithRow("1,0.25,0.5,1,0,0.125,-inf", 6)}}, "m.json", "inf.csv", "o.csv", {},
       {"inf.csv:6:"}},
      {"material index out of range", {{"idx.csv", csvWithRow("3,0.25,0.5,1,0,0.125,1", 3)}}, "m.json", "idx.csv",
       "o.csv", {}, {"idx.csv:3:", "3"}},
      {"negative material index", {{"neg.csv", csvWithRow("-1,0.25,0.5,1,0,0.125,1", 2)}}, "m.json", "neg.csv",
       "o.csv", {}, {"neg.csv:2:"}},
      {"fractional material index", {{"frac.csv", csvWithRow("0.5,0.25,0.5,1,0,0.125,1", 4)}}, "m.json", "frac.csv",
       "o.csv", {}, {"frac.csv:4:"}},
      {"zero-length L", {{"zl.csv", csvWithRow("1,0,0,0,0,0.125,1", 2)}}, "m.json", "zl.csv", "o.csv", {},
       {"zl.csv:2:", "L"}},
      {"zero-length V", {{"zv.csv", csvWithRow("1,0.25,0.5,1,0,-0,0", 6)}}, "m.json", "zv.csv", "o.csv", {},
       {"zv.csv:6:", "V"}},
      {"header only", {{"hdr.csv", "material,Lx,Ly,Lz,Vx,Vy,Vz\n"}}, "m.json", "hdr.csv", "o.csv", {}, {"hdr.csv"}},
      {"empty file", {{"nothing.csv", ""}}, "m.json", "nothing.csv", "o.csv", {}, {"nothing.csv"}},
      {"missing header", {{"nohdr.csv", "1,0.25,0.5,1,0,0.125,1\n"}}, "m.json", "nohdr.csv", "o.csv", {},
       {"nohdr.csv:1:"}},
      {"no material column without --grid", {{"six.csv", "Lx,Ly,Lz,Vx,Vy,Vz\n0.25,0.5,1,0,0.125,1\n"}}, "m.json",
       "six.csv", "o.csv", {}, {"six.csv: header: missing column material", "--grid"}},
      // Samples NPY (rows are 0-based, as numpy indexes them).
      {"NPY NaN", {{"nan.npy", npyWithRow({0, 0.25, nan, 1, 0, 0.125, 1}, 2, true)}}, "m.json", "nan.npy", "o.csv", {},
       {"nan.npy", "row 2"}},
      {"NPY Inf", {{"inf.npy", npyWithRow({0, 0.25, 0.5, 1, inf, 0.125, 1}, 3, false)}}, "m.json", "inf.npy", "o.csv",
       {}, {"inf.npy", "row 3"}},
      {"NPY material index out of range", {{"idx.npy", npyWithRow({7, 0.25, 0.5, 1, 0, 0.125, 1}, 1, false)}}, "m.json",
       "idx.npy", "o.csv", {}, {"idx.npy", "row 1"}},
      {"NPY zero-length V", {{"zv.npy", npyWithRow({0, 0.25, 0.5, 1, 0, 0, 0}, 0, true)}}, "m.json", "zv.npy", "o.csv",
       {}, {"zv.npy", "row 0"}},
      {"NPY wrong shape", {{"shape.npy", brdfcl::test::npyArray(std::vector<double>(10, 0.5), 5, true)}}, "m.json", "shape.npy", "o.csv",
       {}, {"shape.npy", "shape"}},
      {"NPY (N,6) without --grid", {{"six.npy", brdfcl::test::npyArray(std::vector<double>(12, 0.5), 6, true)}}, "m.json", "six.npy",
       "o.csv", {}, {"six.npy", "shape"}},
      {"NPY truncated", {{"cut.npy", npyWithRow({0, 0.25, 0.5, 1, 0, 0.125, 1}, 0, false).substr(0, 200)}}, "m.json",
       "cut.npy", "o.csv", {}, {"cut.npy"}},
      {"not an NPY file", {{"csv.npy", "material,Lx,Ly,Lz,Vx,Vy,Vz\n0,0,0,1,0,0,1\n"}}, "m.json", "csv.npy", "o.csv",
       {}, {"csv.npy"}},
      // The output side and the options, with otherwise good input.
      {"output directory missing", {}, "m.json", "s.csv", "nodir/o.csv", {}, {"nodir/o.csv"}},
      {"unknown lobe", {}, "m.json", "s.csv", "o.csv", {"--lobe", "foo"}, {"--lobe", "foo"}},
      {"unknown option", {}, "m.json", "s.csv", "o.npy", {"--frobnicate"}, {"--frobnicate"}},
      {"bad device index", {}, "m.json", "s.csv", "o.csv", {"--device", "99"}, {"99"}},
      {"no device of that name", {}, "m.json", "s.csv", "o.npy", {"--device", "no-such"}, {"no-such"}},
  };
}

TEST_F(Cli, BadInputIsOneLineErrorAndLeavesNoOutput) {
  std::vector<BadCase> cases = badInputCases();
  // Root reads any file whatever its mode, so the permission case only means something otherwise.
  if (::geteuid() != 0)
    cases.push_back({"unreadable materials", {{"secret.json", kGltf}}, "secret.json", "s.csv", "o.csv", {},
                     {"secret.json", "Permission denied"}});

  for (std::size_t k = 0; k < cases.size(); ++k) {
    const BadCase& c = cases[k];
    SCOPED_TRACE(c.what);
    const fs::path dir = work_ / ("case" + std::to_string(k));
    fs::create_directories(dir / "adir");
    writeFile(dir / "m.json", kGltf);
    writeFile(dir / "s.csv", samplesCsv(standardSamples()));
    for (const auto& [name, content] : c.files) writeFile(dir / name, content);
    if (c.what == "unreadable materials") fs::permissions(dir / "secret.json", fs::perms::none);
    std::vector<std::string> args{"eval", "--materials", (dir / c.materials).string(), "--samples",
                                  (dir / c.samples).string(), "--out", (dir / c.out).string()};
    args.insert(args.end(), c.extra.begin(), c.extra.end());
    const auto listing = [&] {
      std::set<std::string> names;
      for (const auto& e : fs::directory_iterator(dir)) names.insert(e.path().filename().string());
      return names;
    };

    const auto before = listing();
    expectUserError(run(args), c.needles);
    EXPECT_EQ(listing(), before) << "the failed run left files behind";

    // A result from an earlier run must survive a failed one.
    if (fs::exists(dir / c.out) || !fs::exists((dir / c.out).parent_path())) continue;
    writeFile(dir / c.out, "keep me");
    const auto withOld = listing();
    expectUserError(run(args), c.needles);
    EXPECT_EQ(readFile(dir / c.out), "keep me");
    EXPECT_EQ(listing(), withOld) << "the failed run left files behind";
  }
}

TEST_F(Cli, OutputPathThatIsADirectoryIsAUserError) {
  const std::string m = write("m.json", kGltf), s = write("s.csv", samplesCsv(standardSamples()));
  fs::create_directories(work_ / "out.csv");
  const auto before = listWork();
  expectUserError(eval(m, s, path("out.csv")), {"out.csv"});
  EXPECT_EQ(listWork(), before);
}

// ---------------------------------------------------------------------------------------------
// 6. Textures are ignored with one warning per material.

TEST_F(Cli, TextureReferencesWarnOncePerMaterial) {
  const std::string textured = R"({
  "asset": {"version": "2.0"},
  "materials": [
    {"name": "plain", "pbrMetallicRoughness": {"baseColorFactor": [0.8, 0.35, 0.1, 1.0], "metallicFactor": 0.0,
                                               "roughnessFactor": 0.45}},
    {"name": "Velvet Sofa",
     "pbrMetallicRoughness": {"baseColorFactor": [0.3, 0.5, 0.7, 0.5], "metallicFactor": 0.25, "roughnessFactor": 0.6,
                              "baseColorTexture": {"index": 0}, "metallicRoughnessTexture": {"index": 1}},
     "extensions": {
       "KHR_materials_sheen": {"sheenColorFactor": [0.6, 0.4, 0.5], "sheenRoughnessFactor": 0.35,
                               "sheenColorTexture": {"index": 2}},
       "KHR_materials_clearcoat": {"clearcoatFactor": 0.7, "clearcoatRoughnessFactor": 0.2},
       "KHR_materials_anisotropy": {"anisotropyStrength": 0.6, "anisotropyRotation": 0.9}}},
    {"normalTexture": {"index": 3},
     "pbrMetallicRoughness": {"metallicFactor": 0.1, "roughnessFactor": 0.55},
     "extensions": {"KHR_materials_sheen": {"intensityFactor": 0.8}}}
  ]
})";
  const auto samples = standardSamples();
  const std::string s = write("s.csv", samplesCsv(samples));
  const RunResult r = eval(write("tex.gltf", textured), s, path("o.csv"));
  ASSERT_EQ(r.status, 0) << r.describe();
  EXPECT_TRUE(r.errorLines().empty()) << r.describe();
  const auto warnings = r.warningLines();
  ASSERT_EQ(warnings.size(), 2u) << r.describe();
  EXPECT_NE(warnings[0].find("Velvet Sofa"), std::string::npos) << warnings[0];
  EXPECT_NE(warnings[0].find("baseColorTexture"), std::string::npos) << warnings[0];
  EXPECT_NE(warnings[1].find("materials[2]"), std::string::npos) << warnings[1];

  // Factors only: the same numbers as the texture-free document.
  const RunResult plain = eval(write("m.json", kGltf), s, path("plain.csv"));
  ASSERT_EQ(plain.status, 0) << plain.describe();
  EXPECT_EQ(readFile(path("o.csv")), readFile(path("plain.csv")));
}

// A JSON object that is not glTF is fine as long as it has a materials array.
TEST_F(Cli, AcceptsPlainMaterialsObject) {
  const auto samples = standardSamples();
  const std::string doc = R"({"materials": [{}, {"pbrMetallicRoughness": {"metallicFactor": 0.0}}, {}], "other": 1})";
  const RunResult r = eval(write("mats.json", doc), write("s.csv", samplesCsv(samples)), path("o.csv"));
  ASSERT_EQ(r.status, 0) << r.describe();
  std::vector<MaterialParams> materials(3);  // the spec defaults: white, metallic 1, roughness 1
  materials[1].metallic = 0.0f;
  expectMatchesReference(readCsvResult(path("o.csv")).values, materials, samples, EvalOptions{});
}

// ---------------------------------------------------------------------------------------------
// 7. Devices

TEST_F(Cli, DevicesListAndSelection) {
  const RunResult list = run({"devices"});
  ASSERT_EQ(list.status, 0) << list.describe();
  EXPECT_TRUE(list.err.empty()) << list.err;
  std::smatch match;
  ASSERT_TRUE(std::regex_search(list.out, match, std::regex(R"((^|\n)\[0\] ([^\n]+))"))) << list.out;
  const std::string name = match[2];

  const auto samples = standardSamples();
  const std::string m = write("m.json", kGltf), s = write("s.csv", samplesCsv(samples));
  const auto byDefault = evalNpy(m, s);
  EXPECT_EQ(evalNpy(m, s, {"--device", "0"}), byDefault);
  EXPECT_EQ(evalNpy(m, s, {"--device", name.substr(0, std::min<std::size_t>(name.size(), 8))}), byDefault)
      << "selecting '" << name << "' by a name prefix";

  for (const char* bad : {"99", "no-such"}) {
    SCOPED_TRACE(bad);
    expectUserError(eval(m, s, path("o.csv"), {"--device", bad}), {bad});
    EXPECT_FALSE(fs::exists(path("o.csv")));
  }
}

// An index too large for any integer type is still a bad index, not an internal fault.
TEST_F(Cli, HugeDeviceIndexIsAUserError) {
  const std::string m = write("m.json", kGltf), s = write("s.csv", samplesCsv(standardSamples()));
  expectUserError(eval(m, s, path("o.csv"), {"--device", "99999999999999999999999"}), {"99999999999999999999999"});
  EXPECT_FALSE(fs::exists(path("o.csv")));
}

// ---------------------------------------------------------------------------------------------
// 8. Kernels are embedded: the tool runs from any directory, with paths relative to it.

TEST_F(Cli, RunsFromAnotherDirectoryWithRelativePaths) {
  const auto samples = standardSamples();
  write("m.json", kGltf);
  write("s.npy", samplesNpy(samples, true));
  fs::create_directories(work_ / "results");
  const RunResult r = run({"eval", "--materials", "m.json", "--samples", "s.npy", "--out", "results/o.csv"},
                          work_.string());
  ASSERT_EQ(r.status, 0) << r.describe();
  EXPECT_TRUE(r.err.empty()) << r.err;
  const auto out = readCsvResult(work_ / "results" / "o.csv");
  expectMatchesReference(out.values, gltfMaterials(), samples, EvalOptions{});
  EXPECT_EQ(listWork(), (std::set<std::string>{"m.json", "s.npy", "results", "results/o.csv"}));
}

}  // namespace
