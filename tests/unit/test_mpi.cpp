// brdfcl under `mpirun --oversubscribe -n 3`: eval (CSV, NPY, --grid), render and shade give the
// bytes of one process; a bad row in the last rank's range and an unreadable input give one line
// from rank 0, exit status 2 and no output file. Skipped, with a message, where mpirun is absent.
#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <random>
#include <sstream>
#include <string>
#include <vector>

#include "brdfcl/error.hpp"
#include "brdfcl/io.hpp"
#include "host/src/mpi/session.hpp"
#include "process.hpp"

namespace fs = std::filesystem;
using brdfcl::test::RunResult;
using brdfcl::test::ScratchDir;
using brdfcl::test::slurp;

namespace {

constexpr int kRanks = 3;
constexpr int kRows = 1000;  // rank shares: [0, 334), [334, 667), [667, 1000)

std::string findMpirun() {
  const char* path = std::getenv("PATH");
  std::stringstream dirs(path ? path : "");
  for (std::string dir; std::getline(dirs, dir, ':');) {
    const std::string candidate = (dir.empty() ? "." : dir) + "/mpirun";
    if (::access(candidate.c_str(), X_OK) == 0) return candidate;
  }
  return "";
}

void writeText(const std::string& path, const std::string& text) {
  std::ofstream(path, std::ios::binary) << text;
}

const char* kMaterials = R"({"materials": [
  {"pbrMetallicRoughness": {"baseColorFactor": [0.35, 0.02, 0.04, 1], "metallicFactor": 0, "roughnessFactor": 0.9},
   "extensions": {"KHR_materials_sheen": {"sheenColorFactor": [1, 0.3, 0.35], "sheenRoughnessFactor": 0.4}}},
  {"pbrMetallicRoughness": {"metallicFactor": 1, "roughnessFactor": 0.3},
   "extensions": {"KHR_materials_clearcoat": {"clearcoatFactor": 1, "clearcoatRoughnessFactor": 0.2}}},
  {"pbrMetallicRoughness": {"metallicFactor": 0, "roughnessFactor": 0.5},
   "extensions": {"KHR_materials_anisotropy": {"anisotropyStrength": 0.6, "anisotropyRotation": 0.5}}},
  {"pbrMetallicRoughness": {"metallicFactor": 0.5, "roughnessFactor": 0.2}}
]})";

// kRows random samples (material, L, V) as float32-exact numbers, so CSV and NPY hold the same.
std::vector<std::vector<float>> sampleRows() {
  std::mt19937 rng(13);
  std::uniform_real_distribution<float> u(-1.0f, 1.0f), up(0.05f, 1.0f);
  std::vector<std::vector<float>> rows;
  for (int i = 0; i < kRows; ++i)
    rows.push_back({float(i % 4), u(rng), u(rng), up(rng), u(rng), u(rng), up(rng)});
  return rows;
}

std::string csvOf(const std::vector<std::vector<float>>& rows) {
  std::ostringstream s;
  s.precision(9);
  s << "material,Lx,Ly,Lz,Vx,Vy,Vz\n";
  for (const auto& r : rows)
    for (std::size_t k = 0; k < r.size(); ++k) s << r[k] << (k + 1 < r.size() ? "," : "\n");
  return s.str();
}

std::string npyOf(const std::vector<std::vector<float>>& rows) {
  std::string header = "{'descr': '<f4', 'fortran_order': False, 'shape': (" + std::to_string(rows.size()) + ", 7), }";
  while ((10 + header.size() + 1) % 64 != 0) header += ' ';
  header += '\n';
  std::string out = "\x93NUMPY";
  out += '\x01';
  out += '\x00';
  out += char(header.size() & 0xff);
  out += char(header.size() >> 8);
  out += header;
  for (const auto& r : rows) out.append(reinterpret_cast<const char*>(r.data()), r.size() * sizeof(float));
  return out;
}

// All rows of a stream read in chunks of `chunk`, concatenated.
brdfcl::Samples readAll(brdfcl::SampleStream& stream, std::size_t chunk) {
  brdfcl::Samples all, part;
  while (stream.next(chunk, part)) {
    all.material.insert(all.material.end(), part.material.begin(), part.material.end());
    all.L.insert(all.L.end(), part.L.begin(), part.L.end());
    all.V.insert(all.V.end(), part.V.begin(), part.V.end());
  }
  return all;
}

// The pieces the ranks rely on, in one process (these run without mpirun too).
TEST(RowShares, CoverEveryRowOnceInRankOrder) {
  for (std::uint64_t total : {0, 1, 2, 3, 10, 1000, 1001}) {
    for (int size : {1, 2, 3, 7}) {
      std::uint64_t next = 0;
      for (int r = 0; r < size; ++r) {
        const auto share = brdfcl::mpi::shareOf(total, r, size);
        EXPECT_EQ(share.begin, next);
        EXPECT_LE(share.count(), total / size + 1);
        EXPECT_GE(share.count(), total / size);
        next = share.end;
      }
      EXPECT_EQ(next, total);
    }
  }
  EXPECT_FALSE(brdfcl::mpi::Session::get().active()) << "MPI must not start outside mpirun";
}

TEST(RowShares, SelectedRowsAreTheWholeFilesRows) {
  ScratchDir dir("rowshares");
  const auto rows = sampleRows();
  // CRLF, blank lines at the end, no final newline: the CSV readers' edge cases.
  std::string csv = csvOf(rows);
  writeText(dir.path("s.csv"), csv);
  std::string crlf;
  for (char c : csv) crlf += c == '\n' ? std::string("\r\n") : std::string(1, c);
  writeText(dir.path("crlf.csv"), crlf + " \r\n\n\t\n");
  writeText(dir.path("open.csv"), csv.substr(0, csv.size() - 1));
  writeText(dir.path("s.npy"), npyOf(rows));
  for (const char* name : {"s.csv", "crlf.csv", "open.csv", "s.npy"}) {
    brdfcl::SampleStream whole(dir.path(name), 4, false);
    EXPECT_EQ(whole.countRows(), rows.size()) << name;
    const brdfcl::Samples expected = readAll(whole, 1u << 20);
    for (int size : {1, 3, 7}) {
      brdfcl::Samples joined;
      for (int r = 0; r < size; ++r) {
        const auto share = brdfcl::mpi::shareOf(rows.size(), r, size);
        brdfcl::SampleStream part(dir.path(name), 4, false);
        part.selectRows(share.begin, share.count());
        const brdfcl::Samples got = readAll(part, 37);
        EXPECT_EQ(got.size(), share.count()) << name;
        joined.material.insert(joined.material.end(), got.material.begin(), got.material.end());
        joined.L.insert(joined.L.end(), got.L.begin(), got.L.end());
        joined.V.insert(joined.V.end(), got.V.begin(), got.V.end());
      }
      EXPECT_EQ(joined.material, expected.material) << name << " in " << size;
      EXPECT_EQ(joined.L, expected.L) << name << " in " << size;
      EXPECT_EQ(joined.V, expected.V) << name << " in " << size;
    }
  }
  // A blank line that ends a range is the error it is in the whole file, with the file's line.
  std::string blank = csv;
  std::size_t at = 0;
  for (int line = 1; line < 10; ++line) at = blank.find('\n', at) + 1;
  blank.replace(at, blank.find('\n', at) - at, "");  // line 10, row 8
  writeText(dir.path("blank.csv"), blank);
  brdfcl::SampleStream part(dir.path("blank.csv"), 4, false);
  part.selectRows(0, 9);
  try {
    readAll(part, 4);
    FAIL() << "no error";
  } catch (const brdfcl::Error& e) {
    EXPECT_EQ(std::string(e.what()).rfind(dir.path("blank.csv") + ":10: empty line", 0), 0u) << e.what();
  }
}

class Mpi : public ::testing::Test {
 protected:
  void SetUp() override {
    mpirun_ = findMpirun();
    if (mpirun_.empty()) GTEST_SKIP() << "mpirun is not on PATH; install openmpi-bin (make deps) to run the MPI tests";
    rows_ = sampleRows();
    writeText(dir_.path("m.json"), kMaterials);
    writeText(dir_.path("s.csv"), csvOf(rows_));
    writeText(dir_.path("s.npy"), npyOf(rows_));
  }

  // One process, as always.
  RunResult one(const std::vector<std::string>& args) const {
    std::vector<std::string> argv{BRDFCL_CLI_PATH};
    argv.insert(argv.end(), args.begin(), args.end());
    return brdfcl::test::runProcess(argv, runs_.dir(), dir_.dir());
  }

  // The same command line under mpirun -n 3; -q keeps mpirun's own notes (a non-zero exit status)
  // off stderr, so that what is left is brdfcl's.
  RunResult many(const std::vector<std::string>& args) const {
    std::vector<std::string> argv{mpirun_, "-q", "--oversubscribe"};
    if (::geteuid() == 0) argv.push_back("--allow-run-as-root");  // CI containers run as root
    argv.insert(argv.end(), {"-n", std::to_string(kRanks), BRDFCL_CLI_PATH});
    argv.insert(argv.end(), args.begin(), args.end());
    brdfcl::test::ProcessOptions o;
    o.cwd = dir_.dir();
    // Shared-memory transport without the kernel's cross-memory attach, which containers forbid.
    o.env["OMPI_MCA_btl_vader_single_copy_mechanism"] = "none";
    // make test-asan: Open MPI leaves allocations of plugins it has unloaded by exit, which
    // LeakSanitizer reports from "<unknown module>" and no suppression can name. Leaks of brdfcl's
    // own code are checked by the one-process tests; memory errors still abort these runs.
    if (const char* asan = std::getenv("ASAN_OPTIONS"); asan != nullptr)
      o.env["ASAN_OPTIONS"] = std::string(asan) + ":detect_leaks=0";
    return brdfcl::test::runProcess(argv, runs_.dir(), o);
  }

  // Runs `args` once alone (output `name1`) and once under mpirun (`name3`); both must succeed
  // with the same bytes.
  void expectSameBytes(std::vector<std::string> args, const std::string& outOption, const std::string& extension) {
    std::vector<std::string> a1 = args, a3 = args;
    a1.insert(a1.end(), {outOption, "one" + extension});
    a3.insert(a3.end(), {outOption, "three" + extension});
    const RunResult r1 = one(a1);
    ASSERT_EQ(r1.status, 0) << r1.describe();
    const RunResult r3 = many(a3);
    ASSERT_EQ(r3.status, 0) << r3.describe();
    EXPECT_EQ(r3.err, "") << r3.describe();
    const std::string b1 = slurp(dir_.path("one" + extension)), b3 = slurp(dir_.path("three" + extension));
    ASSERT_FALSE(b1.empty());
    EXPECT_TRUE(b1 == b3) << "mpirun -n 3 wrote " << b3.size() << " bytes, one process " << b1.size();
  }

  // The failure contract: status 2, the one line one process prints, no output, no temporaries.
  void expectOneLineFailure(const std::vector<std::string>& args, const std::string& out) {
    const auto before = dir_.list();
    const RunResult r1 = one(args);
    ASSERT_EQ(r1.status, 2) << r1.describe();
    const RunResult r3 = many(args);
    EXPECT_EQ(r3.status, 2) << r3.describe();
    EXPECT_EQ(r3.err, r1.err) << r3.describe();
    EXPECT_EQ(std::count(r3.err.begin(), r3.err.end(), '\n'), 1) << r3.describe();
    EXPECT_FALSE(fs::exists(dir_.path(out)));
    EXPECT_EQ(dir_.list(), before) << "a run left files behind";
  }

  std::string mpirun_;
  std::vector<std::vector<float>> rows_;
  ScratchDir dir_{"mpi"}, runs_{"mpi-runs"};
};

TEST_F(Mpi, EvalCsvAndNpyMatchOneProcess) {
  expectSameBytes({"eval", "--materials", "m.json", "--samples", "s.csv"}, "--out", ".csv");
  expectSameBytes({"eval", "--materials", "m.json", "--samples", "s.npy"}, "--out", ".npy");
  // Chunks smaller than a rank's share, and CSV in, NPY out.
  expectSameBytes({"eval", "--materials", "m.json", "--samples", "s.csv", "--chunk", "57"}, "--out", ".npy");
}

TEST_F(Mpi, EvalWithFewerRowsThanRanks) {
  writeText(dir_.path("two.csv"), csvOf({rows_[0], rows_[1]}));
  expectSameBytes({"eval", "--materials", "m.json", "--samples", "two.csv"}, "--out", ".csv");
}

TEST_F(Mpi, GridSplitsByMaterialBlockAndMatchesOneProcess) {
  expectSameBytes({"eval", "--grid", "--materials", "m.json", "--samples", "s.npy"}, "--out", ".npy");
  expectSameBytes({"eval", "--grid", "--materials", "m.json", "--samples", "s.csv", "--chunk", "100"}, "--out", ".csv");
}

TEST_F(Mpi, RenderAndShadeMatchOneProcess) {
  expectSameBytes({"render", "--size", "40x30"}, "--out", ".png");
  expectSameBytes({"render", "--size", "40x30"}, "--out", ".exr");
  ASSERT_EQ(one({"gbuffer", "--size", "40x30", "--out", "g.exr"}).status, 0);
  writeText(dir_.path("scene.json"), "{}");
  expectSameBytes({"shade", "--gbuffer", "g.exr", "--scene", "scene.json"}, "--out", ".exr");
}

TEST_F(Mpi, GltfRenderMatchesOneProcess) {
  // The demo's sphere sweep as a .glb: textures in every extension slot, lights, a camera.
  const RunResult demo = one({"demo", "--size", "24x24", "--spp", "1"});
  ASSERT_EQ(demo.status, 0) << demo.describe();
  expectSameBytes({"render", "--gltf", "out/demo.glb", "--size", "40x30", "--spp", "2"}, "--out", ".exr");
}

TEST_F(Mpi, BadRowInTheLastRanksRange) {
  auto rows = rows_;
  rows[950][1] = rows[950][2] = rows[950][3] = 0.0f;  // L of zero length
  writeText(dir_.path("bad.csv"), csvOf(rows));
  writeText(dir_.path("bad.npy"), npyOf(rows));
  expectOneLineFailure({"eval", "--materials", "m.json", "--samples", "bad.csv", "--out", "o.csv"}, "o.csv");
  EXPECT_NE(many({"eval", "--materials", "m.json", "--samples", "bad.csv", "--out", "o.csv"}).err.find("bad.csv:952:"),
            std::string::npos);
  expectOneLineFailure({"eval", "--materials", "m.json", "--samples", "bad.npy", "--out", "o.npy"}, "o.npy");
  EXPECT_NE(many({"eval", "--materials", "m.json", "--samples", "bad.npy", "--out", "o.npy"}).err.find("row 950"),
            std::string::npos);
}

TEST_F(Mpi, BlankLineEndingAMiddleRanksRange) {
  // Row 666 is the last of rank 1: read alone its blank line would look like the file's end.
  std::string csv = csvOf(rows_);
  std::size_t at = 0;
  for (int line = 1; line < 668; ++line) at = csv.find('\n', at) + 1;
  csv.replace(at, csv.find('\n', at) - at, "");
  writeText(dir_.path("blank.csv"), csv);
  expectOneLineFailure({"eval", "--materials", "m.json", "--samples", "blank.csv", "--out", "o.csv"}, "o.csv");
}

TEST_F(Mpi, UnreadableInput) {
  fs::create_directory(dir_.path("adir"));
  expectOneLineFailure({"eval", "--materials", "m.json", "--samples", "missing.csv", "--out", "o.csv"}, "o.csv");
  expectOneLineFailure({"eval", "--materials", "m.json", "--samples", "adir", "--out", "o.npy"}, "o.npy");
  expectOneLineFailure({"shade", "--gbuffer", "missing.exr", "--scene", "m.json", "--out", "o.exr"}, "o.exr");
}

TEST_F(Mpi, EvalFromStdinIsRefused) {
  const RunResult r = many({"eval", "--materials", "m.json", "--samples", "-", "--out", "o.csv"});
  EXPECT_EQ(r.status, 2) << r.describe();
  EXPECT_EQ(r.err,
            "brdfcl: --samples -: under mpirun only rank 0 can read stdin; give the samples as a file every rank can "
            "read\n");
  EXPECT_FALSE(fs::exists(dir_.path("o.csv")));
}

TEST_F(Mpi, EvalToStdoutIsRefused) {
  const RunResult r = many({"eval", "--materials", "m.json", "--samples", "s.csv", "--out", "-"});
  EXPECT_EQ(r.status, 2) << r.describe();
  EXPECT_EQ(r.out, "");
  EXPECT_EQ(r.err,
            "brdfcl: --out '-': under mpirun, outputs must be files (the ranks write their parts into one file); run "
            "one process to write to stdout or a FIFO\n");
}

}  // namespace
