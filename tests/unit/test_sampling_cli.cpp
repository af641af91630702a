// `brdfcl sample` and `brdfcl pdf` end to end: byte-identical output across chunk sizes for the
// counter-based uniforms, the caller's uniforms giving the same rows, pdf agreeing with sample,
// and each bad input refused with one line, exit 2 and no output file.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <functional>
#include <sstream>
#include <string>
#include <vector>

#include "brdfcl/evaluator.hpp"
#include "brdfcl/error.hpp"
#include "process.hpp"
#include "support.hpp"

namespace brdfcl::test {
namespace {

const char* const kMaterials = R"({"materials": [
  {"pbrMetallicRoughness": {"baseColorFactor": [0.8, 0.4, 0.2, 1], "metallicFactor": 0.1, "roughnessFactor": 0.4},
   "extensions": {"KHR_materials_sheen": {"sheenColorFactor": [0.7, 0.7, 0.7], "sheenRoughnessFactor": 0.5},
                  "KHR_materials_clearcoat": {"clearcoatFactor": 0.5, "clearcoatRoughnessFactor": 0.2},
                  "KHR_materials_anisotropy": {"anisotropyStrength": 0.5, "anisotropyRotation": 0.4}}},
  {"pbrMetallicRoughness": {"metallicFactor": 1.0, "roughnessFactor": 0.2}}]})";

class SamplingCli : public ::testing::Test {
 protected:
  ScratchDir dir_{"sampling"};
  std::string path(const std::string& n) const { return dir_.path(n); }
  RunResult run(std::vector<std::string> args) {
    args.insert(args.begin(), BRDFCL_CLI_PATH);
    return runProcess(args, dir_.dir());
  }
  void SetUp() override {
    writeFile(path("m.json"), kMaterials);
    writeFile(path("views.csv"), "material,Vx,Vy,Vz\n0,0.3,0.1,0.9\n1,0,0.8,0.2\n0,0.9,0,0.05\n");
  }
  // The one error line, exit 2, no output left behind.
  void expectError(const std::vector<std::string>& args, const std::string& message) {
    const RunResult r = run(args);
    EXPECT_EQ(r.status, 2) << r.describe();
    ASSERT_EQ(r.errorLines().size(), 1u) << r.describe();
    EXPECT_EQ(r.errorLines()[0], "brdfcl: " + message) << r.describe();
    EXPECT_FALSE(std::ifstream(path("o.csv")).good()) << "an output was left behind";
  }
};

TEST_F(SamplingCli, CountSeedIsByteIdenticalAcrossChunks) {
  std::string first;
  for (const char* chunk : {"1048576", "7", "1"}) {
    for (const char* ext : {".csv", ".npy"}) {
      const std::string out = path(std::string("o_") + chunk + ext);
      const RunResult r = run({"sample", "--materials", path("m.json"), "--views", path("views.csv"), "--out", out,
                               "--count", "50", "--seed", "42", "--chunk", chunk});
      ASSERT_EQ(r.status, 0) << r.describe();
    }
    const std::string csv = slurp(path(std::string("o_") + chunk + ".csv"));
    if (first.empty()) first = csv;
    EXPECT_EQ(csv, first) << "--chunk " << chunk;
    EXPECT_EQ(slurp(path(std::string("o_") + chunk + ".npy")), slurp(path("o_1048576.npy"))) << "--chunk " << chunk;
  }
  EXPECT_EQ(first.substr(0, first.find('\n')), "Lx,Ly,Lz,pdf,wr,wg,wb");
  EXPECT_EQ(std::count(first.begin(), first.end(), '\n'), 151);
}

// The drawn uniforms written out as u columns give the same rows; pdf agrees with sample's pdf.
TEST_F(SamplingCli, CallerUniformsAndPdfAgree) {
  const RunResult r = run({"sample", "--materials", path("m.json"), "--views", path("views.csv"), "--out",
                           path("drawn.csv"), "--count", "4", "--seed", "9"});
  ASSERT_EQ(r.status, 0) << r.describe();
  std::vector<float> u(3 * 12);
  Evaluator::drawUniforms(9, 0, 12, u.data());
  const float views[3][4] = {{0, 0.3f, 0.1f, 0.9f}, {1, 0, 0.8f, 0.2f}, {0, 0.9f, 0, 0.05f}};
  std::ostringstream withU, samples;
  withU.precision(9);
  withU << "u3,u2,u1,Vz,Vy,Vx,material\n";
  std::istringstream drawn(slurp(path("drawn.csv")));
  std::string line;
  std::getline(drawn, line);
  samples << "material,Lx,Ly,Lz,Vx,Vy,Vz\n";
  std::vector<double> pdfs;
  for (int i = 0; i < 12; ++i) {
    const float* v = views[i / 4];
    withU << u[3 * i + 2] << ',' << u[3 * i + 1] << ',' << u[3 * i] << ',' << v[3] << ',' << v[2] << ',' << v[1] << ','
          << v[0] << '\n';
    std::getline(drawn, line);
    double row[7];
    ASSERT_EQ(std::sscanf(line.c_str(), "%lf,%lf,%lf,%lf,%lf,%lf,%lf", row, row + 1, row + 2, row + 3, row + 4, row + 5,
                          row + 6), 7);
    if (row[3] > 0) {
      samples << v[0] << ',' << line.substr(0, line.find(',', line.find(',', line.find(',') + 1) + 1)) << ',' << v[1]
              << ',' << v[2] << ',' << v[3] << '\n';
      pdfs.push_back(row[3]);
    }
  }
  writeFile(path("u.csv"), withU.str());
  writeFile(path("s.csv"), samples.str());
  const RunResult again = run({"sample", "--materials", path("m.json"), "--views", path("u.csv"), "--out", path("given.csv")});
  ASSERT_EQ(again.status, 0) << again.describe();
  EXPECT_EQ(slurp(path("given.csv")), slurp(path("drawn.csv")));
  const RunResult p = run({"pdf", "--materials", path("m.json"), "--samples", path("s.csv"), "--out", path("p.csv")});
  ASSERT_EQ(p.status, 0) << p.describe();
  std::istringstream in(slurp(path("p.csv")));
  std::getline(in, line);
  EXPECT_EQ(line, "pdf");
  ASSERT_FALSE(pdfs.empty());
  for (double want : pdfs) {
    ASSERT_TRUE(std::getline(in, line));
    EXPECT_NEAR(std::stod(line), want, 1e-4 * want);
  }
}

TEST_F(SamplingCli, BadInputIsOneLineExitTwo) {
  const std::string m = path("m.json"), o = path("o.csv");
  expectError({"sample", "--materials", m, "--views", path("views.csv"), "--out", o},
              "--views '" + path("views.csv") + "' has no u1,u2,u3 columns; add them, or pass --count K (and --seed S)");
  writeFile(path("u.csv"), "material,Vx,Vy,Vz,u1,u2,u3\n0,0,0,1,0.5,0.5,0.5\n0,0,0,1,0.5,1,0.5\n");
  expectError({"sample", "--materials", m, "--views", path("u.csv"), "--out", o},
              path("u.csv") + ":3: field 'u2' must be in [0, 1), got 1");
  writeFile(path("uok.csv"), "material,Vx,Vy,Vz,u1,u2,u3\n0,0,0,1,0.5,0.5,0.5\n");
  expectError({"sample", "--materials", m, "--views", path("uok.csv"), "--out", o, "--count", "3"},
              "--count draws the uniforms, but --views '" + path("uok.csv") + "' has u1,u2,u3 columns; give one or the other");
  writeFile(path("bad.csv"), "material,Vx,Vy,u1,u2,u3\n0,0,0,0.5,0.5,0.5\n");
  expectError({"sample", "--materials", m, "--views", path("bad.csv"), "--out", o},
              path("bad.csv") + ": header: missing column Vz");
  writeFile(path("two.csv"), "material,Vx,Vy,Vz,u1\n0,0,0,1,0.5\n");
  expectError({"sample", "--materials", m, "--views", path("two.csv"), "--out", o},
              path("two.csv") + ": header: give all of u1,u2,u3 or none");
  writeFile(path("idx.csv"), "material,Vx,Vy,Vz\n2,0,0,1\n");
  expectError({"sample", "--materials", m, "--views", path("idx.csv"), "--out", o, "--count", "1"},
              path("idx.csv") + ":2: material index 2 out of range (2 materials)");
  writeFile(path("zero.csv"), "Vx,Vy,Vz\n0,0,0\n");
  expectError({"sample", "--materials", m, "--views", path("zero.csv"), "--out", o, "--count", "1"},
              path("zero.csv") + ":2: V has zero length");
  writeFile(path("nan.csv"), "Vx,Vy,Vz\n0,nan,1\n");
  expectError({"sample", "--materials", m, "--views", path("nan.csv"), "--out", o, "--count", "1"},
              path("nan.csv") + ":2: field 'Vy' is not finite: nan");
  writeFile(path("short.csv"), "Vx,Vy,Vz\n0,1\n");
  expectError({"sample", "--materials", m, "--views", path("short.csv"), "--out", o, "--count", "1"},
              path("short.csv") + ":2: expected 3 numbers (Vx,Vy,Vz), got '0,1'");
  writeFile(path("unknown.csv"), "Vx,Vy,Vz,w\n0,0,1,1\n");
  expectError({"sample", "--materials", m, "--views", path("unknown.csv"), "--out", o, "--count", "1"},
              path("unknown.csv") + ": header: unknown column 'w'; expected material,Vx,Vy,Vz,u1,u2,u3");
  expectError({"sample", "--materials", m, "--views", path("views.csv"), "--out", o, "--count", "-1"},
              "--count -1 is out of range; use 1 to 4294967296");
  expectError({"sample", "--materials", m, "--views", path("views.csv"), "--out", o, "--count", "2", "--chunk", "0"},
              "--chunk 0 is out of range; use 1 to 67108864");
}

TEST_F(SamplingCli, MalformedViewFiles) {
  const std::string m = path("m.json"), o = path("o.csv");
  auto expect = [&](const std::string& file, const std::string& bytes, const std::string& message) {
    writeFile(path(file), bytes);
    std::vector<std::string> args = {"sample", "--materials", m, "--views", path(file), "--out", o, "--count", "1"};
    expectError(args, path(file) + ": " + message);
  };
  expect("twice.csv", "Vx,Vy,Vz,Vx\n0,0,1,0\n", "header: column Vx appears twice");
  expect("empty.csv", "", "empty file; expected a header such as material,Vx,Vy,Vz,u1,u2,u3");
  expect("none.csv", "Vx,Vy,Vz\n", "no views");
  expect("bad.npy", "not numpy at all", "not an NPY file");
  std::string npy = "\x93NUMPY\x01";
  npy += '\0';
  std::string header = "{'descr': '<i4', 'fortran_order': False, 'shape': (1, 3), }";
  header.resize(117, ' ');
  header += '\n';
  npy += char(header.size() & 0xff);
  npy += char(header.size() >> 8);
  expect("int.npy", npy + header + std::string(12, '\0'), "dtype must be float32 or float64 (little-endian)");
  std::string f4 = "{'descr': '<f4', 'fortran_order': False, 'shape': (2, 3), }";
  f4.resize(117, ' ');
  f4 += '\n';
  expect("short.npy", npy + f4 + std::string(12, '\0'), "file is shorter than its shape says");
  std::string five = "{'descr': '<f4', 'fortran_order': False, 'shape': (1, 5), }";
  five.resize(117, ' ');
  five += '\n';
  expect("five.npy", npy + five + std::string(20, '\0'), "shape (N, 5): expected 7, 6, 4 or 3 columns");
  expect("eight.csv", "material,Vx,Vy,Vz,u1,u2,u3,x\n0,0,0,1,0.5,0.5,0.5,1\n",
         "header: more than 7 columns; expected material,Vx,Vy,Vz,u1,u2,u3");
  expect("cut.npy", npy + "\xff\xff{'descr'", "truncated NPY header");
  auto headerOf = [&](std::string dict) {
    dict.resize(117, ' ');
    return npy + dict + '\n';
  };
  expect("fortran.npy", headerOf("{'descr': '<f4', 'fortran_order': True, 'shape': (1, 3), }") + std::string(12, '\0'),
         "must be in C order");
  expect("flat.npy", headerOf("{'descr': '<f4', 'fortran_order': False, 'shape': (3,), }") + std::string(12, '\0'),
         "shape must be (N, 7), (N, 6), (N, 4) or (N, 3)");
  // A good (N, 3) NPY of V alone samples.
  std::string good = npy + f4;
  const float v[6] = {0, 0, 1, 0.5f, 0, 0.5f};
  good.append(reinterpret_cast<const char*>(v), sizeof v);
  writeFile(path("good.npy"), good);
  const RunResult r = run({"sample", "--materials", m, "--views", path("good.npy"), "--out", path("g.npy"), "--count", "3"});
  EXPECT_EQ(r.status, 0) << r.describe();
  EXPECT_EQ(slurp(path("g.npy")).size(), 128u + 6 * 7 * 4);
}

TEST(SamplingLibrary, BadArraysNameTheRow) {
  Evaluator ev(brdfcl::test::runtime(), EvalOptions{});
  const std::vector<MaterialParams> m(1);
  auto message = [](const std::function<void()>& f) {
    try {
      f();
    } catch (const Error& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  const float nan = std::nanf("");
  EXPECT_EQ(message([&] { ev.sample(m, {}, {0, 0, 1, 0, nan, 1}, {0, 0, 0, 0, 0, 0}); }), "row 1: Vy is not finite: nan");
  EXPECT_EQ(message([&] { ev.sample(m, {0, 1}, {0, 0, 1, 0, 0, 1}, {0, 0, 0, 0, 0, 0}); }),
            "row 1: material index 1 out of range (1 materials)");
  EXPECT_EQ(message([&] { ev.sample(m, {}, {0, 0, 1}, {0, 1, 0}); }), "row 0: u2 must be in [0, 1), got 1");
  Samples s;
  s.material = {0};
  s.L = {0, 0, INFINITY};
  s.V = {0, 0, 1};
  EXPECT_EQ(message([&] { ev.pdf(m, s); }), "row 0: Lz is not finite: inf");
}

}  // namespace
}  // namespace brdfcl::test
