// One test per user-facing message of docs/errors.md that no other test file triggers: library
// guards called directly, CLI option checks and environment failures (no OpenCL platform, no
// device, a device too small, too little memory, a full disk) produced for real in child processes.
#include <fcntl.h>
#include <gtest/gtest.h>
#include <malloc.h>
#include <signal.h>
#include <sys/resource.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <ImfChannelList.h>
#include <ImfHeader.h>
#include <ImfOutputFile.h>
#include <atomic>
#include <chrono>
#include <cmath>
#include <csignal>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <map>
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
#include "brdfcl/error.hpp"
#include "brdfcl/evaluator.hpp"
#include "brdfcl/gbuffer.hpp"
#include "brdfcl/image.hpp"
#include "brdfcl/io.hpp"
#include "brdfcl/lut.hpp"
#include "brdfcl/render.hpp"
#include "host/src/runtime/opencl.hpp"
#include "kernels/common/shading_layout.h"

namespace fs = std::filesystem;
using namespace brdfcl;
using brdfcl::test::errorOf;
using brdfcl::test::runtime;

namespace {

using Child = brdfcl::test::RunResult;

class Errors : public ::testing::Test {
 protected:
  // The CLI's captured stdout/stderr sit in root_; the files a test reads and writes in work_.
  void SetUp() override { fs::create_directories(work_); }

  std::string path(const std::string& name) const { return (work_ / name).string(); }
  std::string write(const std::string& name, const std::string& content) const {
    std::ofstream(path(name), std::ios::binary | std::ios::trunc) << content;
    return path(name);
  }
  std::set<std::string> listWork() const {
    std::set<std::string> names;
    for (const auto& e : fs::recursive_directory_iterator(work_)) names.insert(fs::relative(e.path(), work_).string());
    return names;
  }

  // The CLI with `args`; its stdout and stderr stay outside work_, so listWork() shows exactly
  // what it left behind.
  Child cli(const std::vector<std::string>& args, const std::map<std::string, std::string>& env = {},
            std::size_t asMiB = 0) const {
    std::vector<std::string> all{BRDFCL_CLI_PATH};
    all.insert(all.end(), args.begin(), args.end());
    brdfcl::test::ProcessOptions o;
    o.env = env;
    o.addressSpaceMiB = asMiB;
    o.timeout = std::chrono::seconds(180);
    return brdfcl::test::runProcess(all, root_.string(), o);
  }

  // A valid eval run's inputs, so that only the environment or the option under test can fail.
  std::vector<std::string> evalArgs(const std::string& out) const {
    write("m.json", R"({"materials": [{"pbrMetallicRoughness": {"roughnessFactor": 0.5}}]})");
    write("s.csv", "material,Lx,Ly,Lz,Vx,Vy,Vz\n0,0,0,1,0.6,0,0.8\n");
    return {"eval", "--materials", path("m.json"), "--samples", path("s.csv"), "--out", out};
  }

  // The one-line contract: "brdfcl: <message>\n" on stderr and exit status 2.
  void expectUserError(const Child& c, const std::string& message) const {
    EXPECT_EQ(c.status, 2) << c.err;
    EXPECT_EQ(c.err, "brdfcl: " + message + "\n");
  }

  // An OpenCL vendors directory holding only PoCL's ICD: the tests that steer PoCL with its
  // environment variables must not see another driver the machine may have.
  std::string poclOnlyVendors() const {
    const fs::path icd = "/etc/OpenCL/vendors/pocl.icd";
    if (!fs::exists(icd)) return "";
    const fs::path dir = root_ / "vendors-pocl";
    fs::create_directories(dir);
    fs::copy_file(icd, dir / "pocl.icd", fs::copy_options::overwrite_existing);
    return dir.string();
  }

  brdfcl::test::ScratchDir scratch_{"err"};
  const fs::path root_ = scratch_.dir(), work_ = root_ / "work";
};

// ---------------------------------------------------------------------------------------------
// OpenCL runtime and evaluation

// ocl-icd reads its drivers from $OCL_ICD_VENDORS instead of /etc/OpenCL/vendors: an empty
// directory is a machine without any OpenCL driver.
TEST_F(Errors, NoOpenClPlatform) {
  const fs::path empty = root_ / "vendors-empty";
  fs::create_directories(empty);
  const std::map<std::string, std::string> env{{"OCL_ICD_VENDORS", empty.string()}};
  const std::string message = "no OpenCL platform found; install pocl-opencl-icd (make deps)";
  expectUserError(cli({"devices"}, env), message);
  expectUserError(cli(evalArgs(path("o.csv")), env), message);
  EXPECT_EQ(listWork(), (std::set<std::string>{"m.json", "s.csv"}));
}

// PoCL alone, told to load no device driver: a platform without devices.
TEST_F(Errors, NoOpenClDevice) {
  const std::string vendors = poclOnlyVendors();
  if (vendors.empty()) GTEST_SKIP() << "PoCL's ICD is not installed";
  const std::map<std::string, std::string> env{{"OCL_ICD_VENDORS", vendors}, {"POCL_DEVICES", "none"}};
  const std::string message = "no OpenCL device found; install pocl-opencl-icd (make deps)";
  expectUserError(cli({"devices"}, env), message);
  expectUserError(cli(evalArgs(path("o.csv")), env), message);
  EXPECT_EQ(listWork(), (std::set<std::string>{"m.json", "s.csv"}));
}

// A device with little memory: POCL_MEMORY_LIMIT=1 gives PoCL 1 GiB of global memory and a
// quarter of it as the largest allocation. A G-buffer just larger than that used to fail in
// clCreateBuffer; launches now go in bands of rows below the limit, so it renders.
TEST_F(Errors, FrameLargerThanTheDeviceAllocationRendersInBands) {
  const std::string vendors = poclOnlyVendors();
  if (vendors.empty()) GTEST_SKIP() << "PoCL's ICD is not installed";
  const std::map<std::string, std::string> env{{"OCL_ICD_VENDORS", vendors}, {"POCL_MEMORY_LIMIT", "1"}};
  const Child devices = cli({"devices"}, env);
  ASSERT_EQ(devices.status, 0) << devices.err;
  std::smatch m;
  ASSERT_TRUE(std::regex_search(devices.out, m, std::regex(R"(max allocation: (\d+) MiB)"))) << devices.out;
  const double maxAlloc = std::stod(m[1]) * (1 << 20);
  const int side = int(std::ceil(std::sqrt(maxAlloc / (4.0 * GB_PLANES)))) + 1;  // GB_PLANES floats per pixel
  ASSERT_LE(side, 3000) << "PoCL ignored POCL_MEMORY_LIMIT";
  const std::string size = std::to_string(side) + "x" + std::to_string(side);
  const Child done = cli({"gbuffer", "--scene", "spheres", "--size", size, "--out", path("g.exr")}, env);
  EXPECT_EQ(done.status, 0) << done.err;
  EXPECT_TRUE(std::filesystem::exists(path("g.exr")));
}

// Every site turns a cl::Error into this message through rethrowOpenCL; here from a real
// failing call on the shared runtime (a buffer of 0 bytes).
TEST_F(Errors, RethrowOpenClFormatsTheFailedCall) {
  EXPECT_EQ(errorOf([] {
              try {
                cl::Buffer b(runtime().opencl().context(), CL_MEM_READ_ONLY, 0);
              } catch (const cl::Error&) {
                rethrowOpenCL("allocating nothing");
              }
            }),
            "allocating nothing: OpenCL call clCreateBuffer failed: CL_INVALID_BUFFER_SIZE (-61)");
}

TEST_F(Errors, LaneWidthOutOfTheSupportedSet) {
  for (const char* w : {"3", "32", "x", "", "16 "}) {
    expectUserError(cli(evalArgs(path("o.csv")), {{"BRDFCL_LANES", w}}),
                    std::string("BRDFCL_LANES=") + w + " is not supported; use 1, 4, 8 or 16");
    EXPECT_EQ(listWork(), (std::set<std::string>{"m.json", "s.csv"})) << w;
  }
}

// A batch of 2^61 samples can never be allocated: the real allocation failure, no limit needed.
TEST_F(Errors, OutOfHostMemoryForABatch) {
  Evaluator ev(runtime(), EvalOptions{});
  const std::vector<MaterialParams> materials(1);
  EXPECT_EQ(errorOf([&] { SoaBatch b(ev, materials, std::size_t(1) << 61); }),
            "out of host memory allocating 8796093022208 MiB for a batch");
  EXPECT_EQ(errorOf([&] { SoaBatch b(ev, materials, SIZE_MAX); }).rfind("out of host memory allocating ", 0), 0u);
}

// The same through the CLI, where it matters: bench's largest batch (1 GiB per plane) under a
// 1 GiB address-space limit. One PoCL thread and one malloc arena keep the process itself
// well below the limit on any machine.
TEST_F(Errors, OutOfHostMemoryInTheCli) {
  if (brdfcl::test::kAddressSanitizer) GTEST_SKIP() << brdfcl::test::kNoAddressSpaceLimitUnderAsan;
  // PoCL alone: another driver (NVIDIA's) may not even load within 1 GiB of address space.
  const std::string vendors = poclOnlyVendors();
  if (vendors.empty()) GTEST_SKIP() << "PoCL's ICD is not installed";
  const Child c = cli({"bench", "--n", "268435456", "--runs", "1"},
                      {{"OCL_ICD_VENDORS", vendors}, {"POCL_MAX_PTHREAD_COUNT", "1"}, {"MALLOC_ARENA_MAX", "1"}}, 1024);
  expectUserError(c, "out of host memory allocating 1024 MiB for a batch");
}

TEST_F(Errors, LibraryEvaluationGuards) {
  Evaluator ev(runtime(), EvalOptions{});
  EXPECT_EQ(errorOf([&] { SoaBatch b(ev, {}, 16); }), "no materials to evaluate");
  Samples s;
  s.L = {0, 0, 1, 0, 0, 1};
  s.V = {0, 0, 1, 0.6f, 0, 0.8f};
  s.material = {0, 2};
  const std::vector<MaterialParams> two(2);
  EXPECT_EQ(errorOf([&] { ev.evaluate(two, s); }), "sample 1: material index 2 out of range (2 materials)");
  s.material = {0, 1};
  s.V[5] = NAN;
  EXPECT_EQ(errorOf([&] { ev.evaluate(two, s); }), "sample 1: Vz is not finite: nan");
  EXPECT_EQ(errorOf([&] { ev.evaluateGrid(two, s); }), "sample 1: Vz is not finite: nan");
  s.V[5] = 0.8f;
  auto bad = two;
  bad[1].roughness = 1.5f;
  EXPECT_EQ(errorOf([&] { ev.evaluate(bad, s); }), "material 1: roughness must be a number in [0, 1], got 1.5");
  bad[1].roughness = 0.5f;
  bad[1].anisotropyRotation = -INFINITY;
  EXPECT_EQ(errorOf([&] { ev.evaluateGrid(bad, s); }), "material 1: anisotropyRotation must be a finite number, got -inf");
  bad[1].anisotropyRotation = 0.0f;
  bad[1].draftIntensity = 1e31f;
  EXPECT_EQ(errorOf([&] { SoaBatch b(ev, bad, 16); }),
            "material 1: draftIntensity must be a number >= 0, got 1e+31 (at most 1e+30: f would overflow float)");
  EXPECT_EQ(errorOf([] { bakeSheenAlbedo(runtime(), SheenDistribution::Charlie, SheenVisibility::Charlie, 1); }),
            "sheen albedo table size 1 is too small; use at least 2");
}

TEST_F(Errors, LutSizeOutOfRange) {
  EXPECT_EQ(errorOf([] { bakeLut(runtime(), LutKind::GgxDfg, 4097); }), "LUT size 4097 is out of range; use 2 to 4096");
  EXPECT_EQ(errorOf([] { bakeLut(runtime(), LutKind::SheenE, 1); }), "LUT size 1 is out of range; use 2 to 4096");
}

// ---------------------------------------------------------------------------------------------
// Command line

TEST_F(Errors, BenchOptionsOutOfRange) {
  expectUserError(cli({"bench", "--n", "0"}), "--n 0 is out of range; use 1 to 268435456");
  expectUserError(cli({"bench", "--n", "268435457"}), "--n 268435457 is out of range; use 1 to 268435456");
  expectUserError(cli({"bench", "--runs", "0"}), "--runs 0 is out of range; use 1 to 1000");
  expectUserError(cli({"bench", "--runs", "1001"}), "--runs 1001 is out of range; use 1 to 1000");
  expectUserError(cli({"bench", "--materials", "0"}), "--materials 0 is out of range; use 1 to 1048576");
  expectUserError(cli({"bench", "--materials", "1048577"}), "--materials 1048577 is out of range; use 1 to 1048576");
  expectUserError(cli({"bench", "--pairs", path("none.f32")}), "--pairs '" + path("none.f32") + "': cannot read: No such file or directory");
  write("odd.f32", std::string(25, '\0'));
  expectUserError(cli({"bench", "--pairs", path("odd.f32")}),
                  "--pairs '" + path("odd.f32") + "' holds 25 bytes; expected six float32 planes of 1 to 268435456 values");
  expectUserError(cli({"bench", "--lobe", "diffuse", "--n", "16", "--runs", "1"}),
                  "unknown --lobe value 'diffuse'; use sheen, specular, clearcoat or all");
}

// Output extensions are checked before any work, so nothing is written.
TEST_F(Errors, RenderAndShadeOutputExtensions) {
  const std::string g = path("g.exr"), s = path("s.json");
  expectUserError(cli({"shade", "--gbuffer", g, "--scene", s, "--out", path("o.exr"), "--png", path("o.jpg")}),
                  "--png '" + path("o.jpg") + "' must end in .png");
  expectUserError(cli({"render", "--size", "8x8", "--out", path("o.jpg")}), "--out '" + path("o.jpg") + "' must end in .png or .exr");
  expectUserError(cli({"render", "--size", "8x8", "--out", path("o.png"), "--exr", path("o.tif")}),
                  "--exr '" + path("o.tif") + "' must end in .exr");
  expectUserError(cli({"gbuffer", "--size", "8x8", "--out", path("g.png")}), "--out '" + path("g.png") + "' must end in .exr");
  EXPECT_TRUE(listWork().empty());
}

// ---------------------------------------------------------------------------------------------
// Materials JSON and samples NPY

TEST_F(Errors, DraftSheenKeys) {
  const auto draft = [](const std::string& key, const std::string& value) {
    return R"({"materials": [{"extensions": {"KHR_materials_sheen": {")" + key + "\": " + value + "}}}]}";
  };
  EXPECT_EQ(errorOf([&] { parseMaterials(draft("intensityFactor", "1e31"), "m.json"); }),
            "m.json: materials[0].extensions.KHR_materials_sheen.intensityFactor: expected a number >= 0, got 1e+31 "
            "(at most 1e+30: f would overflow float)");
  EXPECT_EQ(errorOf([&] { parseMaterials(draft("sheenFactor", "3e38"), "m.json"); }),
            "m.json: materials[0].extensions.KHR_materials_sheen.sheenFactor: expected a number >= 0, got 3e+38 "
            "(at most 1e+30: f would overflow float)");
  EXPECT_EQ(parseMaterials(draft("intensityFactor", "1e30"), "m.json")[0].draftIntensity, 1e30f);
  EXPECT_EQ(errorOf([&] { parseMaterials(draft("sheenFactor", R"(1, "intensityFactor": 1)"), "m.json"); }),
            "m.json: materials[0].extensions.KHR_materials_sheen: has both intensityFactor and sheenFactor (the "
            "draft's two names for one value); keep one");
}

// NPY v1.0 with a hand-written header (padded as numpy pads it) and 7 float64 zeros per row.
std::string npyWithHeader(const std::string& header, std::size_t dataRows = 1) {
  return brdfcl::test::npyWithDict(header) + std::string(dataRows * 7 * 8, '\0');
}

TEST_F(Errors, NpyHeaderSyntax) {
  const std::vector<std::pair<std::string, std::string>> cases = {
      {"{descr: '<f8', 'fortran_order': False, 'shape': (1, 7), }", "expected a quoted string"},
      {"{'descr': '<f8', 'fortran_order': False, 'shape': (1, 7), 'note: 1}", "unterminated string"},
      {"{'descr': '<f8', 'fortran_order': False, 'shape': (1 7), }", "expected ',' or ')' in shape"},
  };
  for (const auto& [header, why] : cases) {
    const std::string p = write("h.npy", npyWithHeader(header));
    const std::string m = errorOf([&] { readSamples(p, 1, false); });
    EXPECT_EQ(m.rfind(p + ": malformed NPY header (" + why + "): " + header.substr(0, 20), 0), 0u) << m;
  }
}

// ---------------------------------------------------------------------------------------------
// Writing outputs

TEST_F(Errors, OutputPathThatIsNotAFileName) {
  for (const std::string p : {path("sub") + "/", path("."), path(".."), work_.string() + "/x/.."}) {
    EXPECT_EQ(errorOf([&] { writeResults(p, {1, 2, 3}); }), "cannot write '" + p + "': not a file name");
    EXPECT_EQ(errorOf([&] { writePng(p, 1, 1, {1, 2, 3}); }), "cannot write '" + p + "': not a file name");
  }
  EXPECT_TRUE(listWork().empty());
}

// A file-size limit stands in for a full disk: write() fails with EFBIG as it fails with ENOSPC.
// Before the PNG was encoded in memory, stb_image_write ignored that failure and a truncated
// image was renamed into place.
class FileSizeLimit {
 public:
  explicit FileSizeLimit(rlim_t bytes) {
    ::getrlimit(RLIMIT_FSIZE, &old_);
    handler_ = std::signal(SIGXFSZ, SIG_IGN);
    struct rlimit small = old_;
    small.rlim_cur = bytes;
    ::setrlimit(RLIMIT_FSIZE, &small);
  }
  ~FileSizeLimit() {
    ::setrlimit(RLIMIT_FSIZE, &old_);
    std::signal(SIGXFSZ, handler_);
  }

 private:
  struct rlimit old_ {};
  void (*handler_)(int) = nullptr;
};

// Noise compresses badly, so the PNG is far larger than the limit.
std::vector<float> noiseImage(int w, int h) {
  std::mt19937 rng(5);
  std::uniform_real_distribution<float> u(0.0f, 4.0f);
  std::vector<float> rgb(3 * std::size_t(w) * h);
  for (float& v : rgb) v = u(rng);
  return rgb;
}

TEST_F(Errors, FullDiskWhileWritingImagesAndLuts) {
  const auto rgb = noiseImage(128, 128);
  const Lut lut = bakeLut(runtime(), LutKind::GgxDfg, 32);
  std::string png, csv, header, exr, rgbExr, gbuffer;
  GBuffer g;
  g.width = g.height = 64;
  g.P = g.N = g.baseColor = std::vector<float>(rgb.begin(), rgb.begin() + 3 * 64 * 64);
  g.metallic = g.roughness = g.mask = std::vector<float>(rgb.begin(), rgb.begin() + 64 * 64);
  write("keep.png", "old");
  std::string keep;
  {
    FileSizeLimit limit(512);  // below even the LUT EXR's header
    png = errorOf([&] { writePng(path("o.png"), 128, 128, rgb); });
    keep = errorOf([&] { writePng(path("keep.png"), 128, 128, rgb); });
    csv = errorOf([&] { writeLut(lut, path("l.csv")); });
    header = errorOf([&] { writeLut(lut, path("l.h")); });
    exr = errorOf([&] { writeLut(lut, path("l.exr")); });
    rgbExr = errorOf([&] { writeExrRgb(path("i.exr"), 128, 128, rgb); });
    gbuffer = errorOf([&] { writeGBuffer(path("g.exr"), g); });
  }
  EXPECT_EQ(png, "cannot write '" + path("o.png") + "': File too large");
  EXPECT_EQ(keep, "cannot write '" + path("keep.png") + "': File too large");
  EXPECT_EQ(csv, "cannot write '" + path("l.csv") + "': File too large");
  EXPECT_EQ(header, "cannot write '" + path("l.h") + "': File too large");
  // OpenEXR words its own failure; the message names the user's file, never the temporary.
  EXPECT_EQ(exr.rfind("cannot write '" + path("l.exr") + "': ", 0), 0u) << exr;
  EXPECT_NE(exr.find("File too large"), std::string::npos) << exr;
  EXPECT_EQ(exr.find(".tmp."), std::string::npos) << exr;
  for (const auto& [m, file] : {std::pair{rgbExr, path("i.exr")}, std::pair{gbuffer, path("g.exr")}}) {
    EXPECT_EQ(m.rfind("cannot write '" + file + "': ", 0), 0u) << m;
    EXPECT_NE(m.find("File too large"), std::string::npos) << m;
    EXPECT_EQ(m.find(".tmp."), std::string::npos) << m;
  }
  EXPECT_EQ(brdfcl::test::slurp(path("keep.png")), "old");
  EXPECT_EQ(listWork(), std::set<std::string>{"keep.png"});
}

// The encoder's own allocation failing. A death test in gtest's "threadsafe" style runs the
// statement in a freshly executed copy of this binary: one thread and one malloc arena, unlike a
// fork of this process, where PoCL's threads' arenas keep reserved address space that malloc can
// still use under the limit. There the address space is capped just above what the image and its
// 8-bit pixels need, so the encoder's buffer of the same size cannot be had; the image is made
// larger than the heap's free space, so no free block can serve it either.
class ErrorsDeathTest : public Errors {};

TEST_F(ErrorsDeathTest, PngEncoderOutOfMemory) {
  if (brdfcl::test::kAddressSanitizer) GTEST_SKIP() << brdfcl::test::kNoAddressSpaceLimitUnderAsan;
  GTEST_FLAG_SET(death_test_style, "threadsafe");
  const std::string out = path("big.png");
  EXPECT_EXIT(
      {
        const std::size_t freeHeap = mallinfo2().fordblks;
        int side = 2048;
        while (3ull * side * side <= freeHeap + (16u << 20)) side *= 2;
        const std::vector<float> rgb(3 * std::size_t(side) * side, 0.5f);
        std::size_t vm = 0;
        std::ifstream status("/proc/self/status");
        for (std::string line; std::getline(status, line);)
          if (line.rfind("VmSize:", 0) == 0) vm = std::stoull(line.substr(7)) << 10;
        struct rlimit limit {};
        limit.rlim_cur = limit.rlim_max = vm + 3ull * side * side + (8u << 20);
        ::setrlimit(RLIMIT_AS, &limit);
        int code = 1;
        try {
          writePng(out, side, side, rgb);
        } catch (const Error& e) {
          std::fprintf(stderr, "%s\n", e.what());
          code = fs::exists(out) || !fs::is_empty(work_) ? 2 : 0;
        }
        std::error_code ec;
        fs::remove_all(root_, ec);  // this copy's own fixture directory: its destructor never runs
        std::fflush(stderr);
        ::_exit(code);
      },
      ::testing::ExitedWithCode(0), "cannot write '.*/big.png': the PNG encoder failed \\(out of memory\\?\\)");
  EXPECT_TRUE(listWork().empty());
}

// ---------------------------------------------------------------------------------------------
// Images, G-buffers and environments

TEST_F(Errors, DeepExrRejected) {
  const std::string p = path("d.exr");
  writeExrRgb(p, 2, 2, std::vector<float>(12, 0.5f));
  std::string bytes = brdfcl::test::slurp(p);
  bytes[5] = char(bytes[5] | 0x08);  // version field bit 11: "non-image" (deep) data
  write("d.exr", bytes);
  int w = 0, h = 0;
  EXPECT_EQ(errorOf([&] { readExrRgb(p, w, h); }),
            p + ": deep OpenEXR file; brdfcl reads flat images only: flatten the deep data");
}

// Only the header matters: the size is checked before a pixel is read.
TEST_F(Errors, ExrImageTooLarge) {
  const std::string p = path("huge.exr");
  {
    Imf::Header header(16385, 16385);
    header.channels().insert("R", Imf::Channel(Imf::HALF));
    header.channels().insert("G", Imf::Channel(Imf::HALF));
    header.channels().insert("B", Imf::Channel(Imf::HALF));
    Imf::OutputFile file(p.c_str(), header);
  }
  int w = 0, h = 0;
  EXPECT_EQ(errorOf([&] { readExrRgb(p, w, h); }), p + ": unsupported image size 16385x16385 (at most 268435456 pixels and 65536 on a side)");
}

TEST_F(Errors, ExrChannelNotInTheFile) {
  const std::string p = path("rgb.exr");
  writeExrRgb(p, 2, 1, std::vector<float>(6, 1.0f));
  int w = 0, h = 0;
  EXPECT_EQ(errorOf([&] {
              readExrChannels(p, [](const std::vector<ExrChannelInfo>&) { return std::vector<std::string>{"R", "Q"}; },
                              w, h);
            }),
            p + ": no channel 'Q'");
}

TEST_F(Errors, EnvironmentTooSmallOrUnknown) {
  const std::string p = path("env.exr");
  writeExrRgb(p, 4, 2, std::vector<float>(24, 1.0f));
  Environment env;
  env.builtin = false;
  env.path = p;
  int w = 0, h = 0;
  EXPECT_EQ(errorOf([&] { environmentPlanes(env, w, h); }), p + ": environment of 4x2 texels is too small; use at least 8x4");
  env.builtin = true;
  env.builtinKind = "forest";
  EXPECT_EQ(errorOf([&] { environmentPlanes(env, w, h); }), "unknown built-in environment 'forest'; use sky, studio or uniform");
}

TEST_F(Errors, GBufferSizeOutOfRange) {
  EXPECT_EQ(errorOf([] { renderSpheresGBuffer(runtime(), spheresScene(), 0, 8); }),
            "image size 0x8 is out of range; use 1 to 16384 per side");
  EXPECT_EQ(errorOf([] { renderSpheresGBuffer(runtime(), spheresScene(), 16385, 1); }),
            "image size 16385x1 is out of range; use 1 to 16384 per side");
}

// A NaN or an infinity a renderer wrote into a G-buffer: the reader names the file, the pixel and
// the channel, so shade fails before preparing its environment and writes nothing; a G-buffer
// built in memory is checked by the shader.
TEST_F(Errors, NonFiniteGBufferValue) {
  GBuffer g;
  g.width = 3;
  g.height = 2;
  const std::size_t n = g.pixelCount();
  g.P.assign(3 * n, 0.0f);
  g.N.assign(3 * n, 0.0f);
  for (std::size_t i = 0; i < n; ++i) g.N[3 * i + 2] = 1.0f;
  g.baseColor.assign(3 * n, 0.5f);
  g.metallic.assign(n, 0.0f);
  g.roughness.assign(n, 0.5f);
  g.mask.assign(n, 1.0f);
  g.roughness[1 * 3 + 2] = NAN;  // pixel (2, 1)
  writeGBuffer(path("g.exr"), g);
  write("s.json", R"({"camera": {"position": [0, 0, 5]}, "lights": [{"type": "directional", "direction": [0, 0, -1]}]})");
  expectUserError(cli({"shade", "--gbuffer", path("g.exr"), "--scene", path("s.json"), "--out", path("o.exr"), "--png",
                       path("o.png")}),
                  path("g.exr") + ": pixel (2, 1) has a non-finite value (nan) in channel 'roughness'; fix the renderer's output");
  EXPECT_EQ(listWork(), (std::set<std::string>{"g.exr", "s.json"}));

  Scene dark;
  dark.environment.builtinKind = "uniform";
  dark.environment.intensity = 0.0f;
  Shader shader(runtime(), dark);
  EXPECT_EQ(errorOf([&] { shader.shade(g); }),
            "G-buffer pixel (2, 1) has a non-finite value (nan) in channel 'roughness'; fix the renderer's output");
  g.roughness[5] = 0.5f;
  g.N[2] = -INFINITY;  // pixel (0, 0)
  EXPECT_EQ(errorOf([&] { shader.shade(g); }),
            "G-buffer pixel (0, 0) has a non-finite value (-inf) in channel 'N.Z'; fix the renderer's output");
  writeGBuffer(path("n.exr"), g);
  EXPECT_EQ(errorOf([&] { readGBuffer(path("n.exr")); }),
            path("n.exr") + ": pixel (0, 0) has a non-finite value (-inf) in channel 'N.Z'; fix the renderer's output");
}

}  // namespace
