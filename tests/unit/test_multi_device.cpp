// --device all and --device 0,1: eval (CSV, NPY, grid), shade and render split across several
// devices give the bytes of a one-device run; bad device lists are one-line errors (exit 2).
// Several devices come from PoCL's POCL_DEVICES="pthread pthread" in the child's environment.
#include <gtest/gtest.h>

#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <random>
#include <sstream>
#include <string>
#include <vector>

#include "host/src/devices/device_set.hpp"
#include "brdfcl/error.hpp"
#include "process.hpp"
#include "support.hpp"

using namespace brdfcl;
using namespace brdfcl::test;

namespace {

const std::map<std::string, std::string> kTwoDevices = {{"POCL_DEVICES", "pthread pthread"}};

class MultiDevice : public testing::Test {
 protected:
  // Byte identity holds between devices of one kind, so the lists name PoCL's devices only,
  // wherever another platform (Intel's, with build/intel-opencl/env sourced) puts them.
  void SetUp() override {
    const RunResult r = cli({"devices"});
    ASSERT_EQ(r.status, 0) << r.describe();
    std::istringstream in(r.out);
    for (std::string line; std::getline(in, line);) {
      if (line.rfind("[", 0) == 0) {
        ++count_;
      } else if (line.find("platform: Portable Computing Language") != std::string::npos) {
        pocl_.push_back(std::to_string(count_ - 1));
      }
    }
    if (pocl_.size() < 2) GTEST_SKIP() << "fewer than two PoCL devices with POCL_DEVICES=\"pthread pthread\":\n" << r.out;
    writeInputs();
  }

  std::string one() const { return pocl_[0]; }
  std::string pair() const { return pocl_[0] + "," + pocl_[1]; }
  std::string reversed() const { return pocl_[1] + "," + pocl_[0]; }
  std::string all() const { return pocl_.size() == count_ ? "all" : pair(); }
  std::string validIndexes() const { return "valid indexes: 0-" + std::to_string(count_ - 1); }

  RunResult cli(std::vector<std::string> args) {
    args.insert(args.begin(), BRDFCL_CLI_PATH);
    ProcessOptions o;
    o.env = kTwoDevices;
    // Under ASan, LeakSanitizer's exit-time scan can crash on the two devices' PoCL worker threads
    // ("Tracer caught signal 11"); leaks are checked by the single-device tests.
    if (const char* asan = std::getenv("ASAN_OPTIONS"); asan != nullptr)
      o.env["ASAN_OPTIONS"] = std::string(asan) + ":detect_leaks=0";
    o.timeout = std::chrono::seconds(300);
    return runProcess(args, dir_.dir(), o);
  }

  // Runs the command with `--device <d>` for each d and expects the same bytes in `out` each time.
  void expectSameOutput(const std::vector<std::string>& args, const std::string& out,
                        const std::vector<std::string>& devices) {
    std::string first;
    for (const auto& d : devices) {
      std::vector<std::string> a = args;
      a.push_back("--device");
      a.push_back(d);
      const RunResult r = cli(a);
      ASSERT_EQ(r.status, 0) << "--device " << d << ": " << r.describe();
      const std::string bytes = slurp(path(out));
      ASSERT_FALSE(bytes.empty()) << "--device " << d;
      if (first.empty()) {
        first = bytes;
      } else {
        EXPECT_TRUE(bytes == first) << out << " differs between --device " << devices[0] << " and --device " << d;
      }
      std::remove(path(out).c_str());
    }
  }

  std::string path(const std::string& name) const { return dir_.path(name); }

 private:
  void writeInputs() {
    std::ofstream m(path("m.json"));
    m << R"({"materials":[
      {"pbrMetallicRoughness":{"baseColorFactor":[0.8,0.3,0.2,1],"roughnessFactor":0.4,"metallicFactor":0.1},
       "extensions":{"KHR_materials_sheen":{"sheenColorFactor":[0.5,0.5,0.9],"sheenRoughnessFactor":0.3},
                     "KHR_materials_clearcoat":{"clearcoatFactor":0.5,"clearcoatRoughnessFactor":0.2}}},
      {"pbrMetallicRoughness":{"roughnessFactor":0.7}},
      {"pbrMetallicRoughness":{"metallicFactor":1,"roughnessFactor":0.2},
       "extensions":{"KHR_materials_anisotropy":{"anisotropyStrength":0.6,"anisotropyRotation":0.5}}}]})";
    std::mt19937_64 rng(seed() ^ 0xde71ce5);
    std::uniform_real_distribution<float> u(-1.0f, 1.0f), up(0.01f, 1.0f);
    // 40 000 samples in chunks of 9 000: several chunks, each split unevenly across the devices.
    std::ofstream s(path("s.csv")), d(path("d.csv"));
    s << "material,Lx,Ly,Lz,Vx,Vy,Vz\n";
    d << "Lx,Ly,Lz,Vx,Vy,Vz\n";
    char line[160];
    for (int i = 0; i < 40000; ++i) {
      std::snprintf(line, sizeof line, "%.6f,%.6f,%.6f,%.6f,%.6f,%.6f\n", u(rng), u(rng), up(rng), u(rng), u(rng), up(rng));
      s << i % 3 << "," << line;
      if (i < 3000) d << line;
    }
  }

  ScratchDir dir_{"multi-device"};
  std::size_t count_ = 0;
  std::vector<std::string> pocl_;
};

TEST_F(MultiDevice, EvalCsvIsByteIdentical) {
  expectSameOutput({"eval", "--materials", path("m.json"), "--samples", path("s.csv"), "--out", path("o.csv"),
                    "--chunk", "9000"},
                   "o.csv", {one(), all(), pair(), reversed()});
}

TEST_F(MultiDevice, EvalNpyIsByteIdentical) {
  expectSameOutput({"eval", "--materials", path("m.json"), "--samples", path("s.csv"), "--out", path("o.npy")}, "o.npy",
                   {one(), all()});
}

// Rows split by material (directions in one chunk), and by direction (a row per chunk).
TEST_F(MultiDevice, GridIsByteIdentical) {
  expectSameOutput({"eval", "--grid", "--materials", path("m.json"), "--samples", path("d.csv"), "--out", path("g.npy")},
                   "g.npy", {one(), all()});
  expectSameOutput({"eval", "--grid", "--materials", path("m.json"), "--samples", path("d.csv"), "--out", path("g.npy"),
                    "--chunk", "1000"},
                   "g.npy", {one(), pair()});
}

TEST_F(MultiDevice, RenderAndShadeAreByteIdentical) {
  expectSameOutput({"render", "--size", "96x61", "--out", path("r.exr")}, "r.exr", {one(), all()});
  const RunResult g = cli({"gbuffer", "--size", "80x53", "--out", path("g.exr"), "--device", one()});
  ASSERT_EQ(g.status, 0) << g.describe();
  std::ofstream(path("scene.json")) << R"({"lights":[{"type":"directional","direction":[0.3,-1,-0.5],"color":[1,1,1],"intensity":3}]})";
  expectSameOutput({"shade", "--gbuffer", path("g.exr"), "--scene", path("scene.json"), "--out", path("s.exr")}, "s.exr",
                   {one(), pair()});
}

TEST_F(MultiDevice, BadListsAreOneLineErrors) {
  const std::vector<std::pair<std::string, std::string>> cases = {
      {"0,9", "--device 0,9: device index 9 out of range; " + validIndexes()},
      {"0,0", "--device 0,0: device 0 is listed twice; " + validIndexes()},
      {"x,1", "--device x,1: 'x' is not a device index; use all or a list such as 0,1; " + validIndexes()},
      {"0,", "--device 0,: '' is not a device index"},
  };
  for (const auto& [list, message] : cases) {
    const RunResult r = cli({"eval", "--materials", path("m.json"), "--samples", path("s.csv"), "--out", path("o.csv"),
                             "--device", list});
    EXPECT_EQ(r.status, 2) << r.describe();
    const auto lines = r.errorLines();
    ASSERT_EQ(lines.size(), 1u) << r.describe();
    EXPECT_EQ(lines[0].rfind("brdfcl: " + message, 0), 0u) << lines[0];
    std::ifstream out(path("o.csv"));
    EXPECT_FALSE(out.good()) << "--device " << list << " left an output file";
  }
  const RunResult r = cli({"render", "--size", "8x8", "--out", path("r.png"), "--device", "0,7"});
  EXPECT_EQ(r.status, 2) << r.describe();
  EXPECT_NE(r.err.find("--device 0,7: device index 7 out of range"), std::string::npos) << r.err;
}

// The library's list parser and the split, without devices.
TEST(DeviceList, ParsesAllAndLists) {
  EXPECT_EQ(parseDeviceList("all", 3), (std::vector<std::size_t>{0, 1, 2}));
  EXPECT_EQ(parseDeviceList("2,0", 3), (std::vector<std::size_t>{2, 0}));
  EXPECT_TRUE(isDeviceList("all"));
  EXPECT_TRUE(isDeviceList("0,1"));
  EXPECT_FALSE(isDeviceList("1"));
  EXPECT_FALSE(isDeviceList("pthread"));
  EXPECT_THROW(parseDeviceList("0,3", 3), Error);
  EXPECT_THROW(parseDeviceList("1,1", 3), Error);
  EXPECT_THROW(parseDeviceList("0,-1", 3), Error);
  EXPECT_THROW(parseDeviceList("0,,1", 3), Error);
}

}  // namespace
