// The eval contract's test bench for test_cli.cpp and test_cli_errors.cpp: standard samples and
// materials, their CSV and NPY files, result readers, the reference values to compare with, and the
// Cli fixture that runs the built binary (BRDFCL_CLI_PATH) in a scratch folder.
#pragma once
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

// Inline, so that both test files share one Cli fixture (GoogleTest requires one class a suite).
namespace brdfcl::test::clieval {

// ---------------------------------------------------------------------------------------------
// Running the binary

using brdfcl::test::RunResult;

inline std::string readFile(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  if (!in) throw std::runtime_error("cannot read " + p.string());
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

inline void writeFile(const fs::path& p, const std::string& content) {
  std::ofstream out(p, std::ios::binary);
  out << content;
  if (!out) throw std::runtime_error("cannot write " + p.string());
}

inline std::atomic<int> dirCounter{0};

// ---------------------------------------------------------------------------------------------
// Test data. Direction components are multiples of 1/256 (or exact powers of two apart), so the
// CSV text, float32 and float64 hold exactly the same numbers and every input format must give
// bit-identical directions to the tool.

using Dir = std::array<double, 3>;
struct Sample {
  std::uint32_t material;
  Dir L, V;
};

inline bool belowHorizon(const Sample& s) { return s.L[2] <= 0.0 || s.V[2] <= 0.0; }

inline Dir quantized(const std::array<float, 3>& unit, double scale) {
  Dir d;
  for (int c = 0; c < 3; ++c) d[c] = std::round(unit[c] * scale * 256.0) / 256.0;
  return d;
}

inline std::vector<Sample> standardSamples() {
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

inline std::string num(double x) {
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.17g", x);  // exact for the dyadic values used here
  return buf;
}

inline std::string samplesCsv(const std::vector<Sample>& samples, bool withMaterial = true) {
  std::string t = withMaterial ? "material,Lx,Ly,Lz,Vx,Vy,Vz\n" : "Lx,Ly,Lz,Vx,Vy,Vz\n";
  for (const auto& s : samples) {
    if (withMaterial) t += std::to_string(s.material) + ",";
    t += num(s.L[0]) + "," + num(s.L[1]) + "," + num(s.L[2]) + "," + num(s.V[0]) + "," + num(s.V[1]) + "," +
         num(s.V[2]) + "\n";
  }
  return t;
}

inline std::string samplesNpy(const std::vector<Sample>& samples, bool float32, bool withMaterial = true) {
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
inline const char* kGltf = R"({
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

inline std::vector<MaterialParams> gltfMaterials() {
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

inline CsvResult readCsvResult(const fs::path& p) {
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

inline std::vector<double> readNpyResult(const fs::path& p) {
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
inline bool hasNineSignificantDigits(const std::string& text) {
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

inline ref::Vec3 normalizedFloat(const Dir& d) {
  const double len = std::sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
  return {double(float(d[0] / len)), double(float(d[1] / len)), double(float(d[2] / len))};
}

// Relative to the value itself: the sheen colors are moderate, so the albedo scaling never
// amplifies the table's error past 1e-3 (test_accuracy covers the extreme colors).
inline void expectMatchesReference(const std::vector<double>& got, const std::vector<MaterialParams>& materials,
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
inline void expectClose(const std::vector<double>& a, const std::vector<double>& b, double rel, double abs,
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

}  // namespace brdfcl::test::clieval
