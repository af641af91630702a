// The output-file layer: "-" is stdout, symlinks are followed and stay links, FIFOs are
// written in place, directories and unknown results extensions are refused before anything is
// written, signals remove temporaries (exit 128 + signal), stale temporaries of dead processes go.
#include <fcntl.h>
#include <gtest/gtest.h>
#include <signal.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <functional>
#include <string>
#include <thread>
#include <vector>

#include "brdfcl/error.hpp"
#include "brdfcl/image.hpp"
#include "brdfcl/io.hpp"
#include "brdfcl/lut.hpp"
#include "host/src/io/output.hpp"
#include "process.hpp"

namespace fs = std::filesystem;
using brdfcl::test::RunResult;
using brdfcl::test::ScratchDir;
using brdfcl::test::deadPid;
using brdfcl::test::slurp;

namespace {

void writeFile(const std::string& p, const std::string& content) {
  std::ofstream out(p, std::ios::binary);
  out << content;
  ASSERT_TRUE(out.good()) << p;
}

std::string errorOf(const std::function<void()>& f) {
  try {
    f();
  } catch (const brdfcl::Error& e) {
    return e.what();
  }
  return "(no error)";
}

bool hasTemporary(const ScratchDir& d) {
  for (const auto& n : d.list())
    if (n.find(".tmp.") != std::string::npos) return true;
  return false;
}

std::vector<float> someRows(std::size_t rows) {
  std::vector<float> v(3 * rows);
  for (std::size_t i = 0; i < v.size(); ++i) v[i] = float(i % 1000) / 7.0f;
  return v;
}

// The bytes writeResults puts in a regular file: what every other kind of target must receive.
std::string regularBytes(const std::function<void(const std::string&)>& write, const std::string& name) {
  ScratchDir d("out-ref");
  write(d.path(name));
  return slurp(d.path(name));
}

// Runs `write` on `fifo` while a reader drains it; returns what the reader got. The reader opens
// without blocking and stops at end of file only once `write` has returned, so a writer that
// replaces the FIFO instead of writing it makes the reader get nothing rather than hang.
std::string throughFifo(const std::string& fifo, const std::function<void()>& write) {
  EXPECT_EQ(::mkfifo(fifo.c_str(), 0600), 0) << std::strerror(errno);
  const int fd = ::open(fifo.c_str(), O_RDONLY | O_NONBLOCK);
  EXPECT_GE(fd, 0) << std::strerror(errno);
  std::atomic<bool> done{false};
  std::string got;
  std::thread reader([&] {
    char buf[65536];
    for (;;) {
      const ssize_t n = ::read(fd, buf, sizeof buf);
      if (n > 0) {
        got.append(buf, std::size_t(n));
      } else if (n == 0 && done.load()) {
        break;
      } else {
        std::this_thread::sleep_for(std::chrono::milliseconds(1));
      }
    }
  });
  try {
    write();
  } catch (...) {
    done = true;
    reader.join();
    ::close(fd);
    throw;
  }
  done = true;
  reader.join();
  ::close(fd);
  return got;
}

// Runs `write` with this process's stdout redirected to a file; returns what it wrote there.
std::string captureStdout(const std::function<void()>& write) {
  ScratchDir d("out-stdout");
  std::fflush(stdout);
  const int saved = ::dup(1);
  const int fd = ::open(d.path("captured").c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0600);
  ::dup2(fd, 1);
  ::close(fd);
  try {
    write();
  } catch (...) {
    ::dup2(saved, 1);
    ::close(saved);
    throw;
  }
  ::dup2(saved, 1);
  ::close(saved);
  return slurp(d.path("captured"));
}

RunResult runCli(const std::vector<std::string>& args, const ScratchDir& d) {
  std::vector<std::string> argv{BRDFCL_CLI_PATH};
  argv.insert(argv.end(), args.begin(), args.end());
  ScratchDir io("out-io");
  return brdfcl::test::runProcess(argv, io.dir(), d.dir());
}

const char* kMaterials = R"({"materials": [{"pbrMetallicRoughness": {"roughnessFactor": 0.5},
  "extensions": {"KHR_materials_sheen": {"sheenColorFactor": [0.5, 0.4, 0.3], "sheenRoughnessFactor": 0.4}}}]})";
const char* kSamples = "material,Lx,Ly,Lz,Vx,Vy,Vz\n0,0,0,1,0,0,1\n0,0.5,0,1,0,0.25,1\n0,-0.5,0.5,1,0.5,0,1\n";

brdfcl::Lut smallLut(int channels) {
  brdfcl::Lut lut{channels == 2 ? brdfcl::LutKind::GgxDfg : brdfcl::LutKind::CharlieDfg, 3, channels, {}, {}, {}};
  for (std::size_t k = 0; k < 9 * std::size_t(channels); ++k) lut.values.push_back(0.125f * float(k));
  return lut;
}

// ---- symlinks ----

TEST(OutputFiles, SymlinkIsFollowedAndStaysALink) {
  ScratchDir d("out-link");
  fs::create_directory(d.path("real"));
  writeFile(d.path("real/r.csv"), "old\n");
  fs::create_symlink(d.path("real/r.csv"), d.path("link.csv"));
  brdfcl::writeResults(d.path("link.csv"), {1, 2, 3});
  EXPECT_TRUE(fs::is_symlink(d.path("link.csv")));
  EXPECT_EQ(fs::read_symlink(d.path("link.csv")), fs::path(d.path("real/r.csv")));
  EXPECT_EQ(slurp(d.path("real/r.csv")), "r,g,b\n1,2,3\n");
  EXPECT_EQ(d.list(), (std::vector<std::string>{"link.csv", "real"}));
  EXPECT_EQ(fs::directory_iterator(d.path("real"))->path().filename(), "r.csv");
  EXPECT_EQ(std::distance(fs::directory_iterator(d.path("real")), fs::directory_iterator()), 1);
}

TEST(OutputFiles, SymlinkChainWithRelativeTargetsIsFollowedToTheEnd) {
  ScratchDir d("out-chain");
  fs::create_directories(d.path("a/b"));
  writeFile(d.path("a/b/final.png"), "old");
  // top.png -> a/mid.png -> b/final.png: each relative target resolves against its link's folder.
  fs::create_symlink("b/final.png", d.path("a/mid.png"));
  fs::create_symlink("a/mid.png", d.path("top.png"));
  brdfcl::writePng(d.path("top.png"), 1, 1, {0.5f, 0.5f, 0.5f});
  EXPECT_TRUE(fs::is_symlink(d.path("top.png")));
  EXPECT_TRUE(fs::is_symlink(d.path("a/mid.png")));
  const std::string png = slurp(d.path("a/b/final.png"));
  EXPECT_EQ(png.substr(1, 3), "PNG");
  EXPECT_EQ(png, regularBytes([](const std::string& p) { brdfcl::writePng(p, 1, 1, {0.5f, 0.5f, 0.5f}); }, "x.png"));
  // A dangling link gets its target created, the link kept.
  fs::create_symlink("new.csv", d.path("dangling.csv"));
  brdfcl::writeResults(d.path("dangling.csv"), {4, 5, 6});
  EXPECT_TRUE(fs::is_symlink(d.path("dangling.csv")));
  EXPECT_EQ(slurp(d.path("new.csv")), "r,g,b\n4,5,6\n");
  EXPECT_FALSE(hasTemporary(d));
}

TEST(OutputFiles, SymlinkLoopIsAOneLineError) {
  ScratchDir d("out-loop");
  fs::create_symlink("b.csv", d.path("a.csv"));
  fs::create_symlink("a.csv", d.path("b.csv"));
  EXPECT_EQ(errorOf([&] { brdfcl::writeResults(d.path("a.csv"), {1, 2, 3}); }),
            "cannot write '" + d.path("a.csv") + "': Too many levels of symbolic links");
  EXPECT_EQ(d.list(), (std::vector<std::string>{"a.csv", "b.csv"}));
}

// ---- FIFOs ----

TEST(OutputFiles, FifoIsWrittenInPlace) {
  ScratchDir d("out-fifo");
  // More rows than a pipe buffers, so the writer must stream while the reader drains.
  const auto rgb = someRows(20000);
  const std::string got = throughFifo(d.path("r.csv"), [&] { brdfcl::writeResults(d.path("r.csv"), rgb); });
  EXPECT_EQ(got, regularBytes([&](const std::string& p) { brdfcl::writeResults(p, rgb); }, "r.csv"));
  EXPECT_EQ(fs::status(d.path("r.csv")).type(), fs::file_type::fifo);
  EXPECT_EQ(d.list(), (std::vector<std::string>{"r.csv"}));
}

TEST(OutputFiles, FifoGetsNpyAndExrThroughASpool) {
  ScratchDir d("out-fifo-seek");
  const auto rgb = someRows(5000);
  EXPECT_EQ(throughFifo(d.path("r.npy"), [&] { brdfcl::writeResults(d.path("r.npy"), rgb); }),
            regularBytes([&](const std::string& p) { brdfcl::writeResults(p, rgb); }, "r.npy"));
  const std::vector<float> img = someRows(64 * 32);
  EXPECT_EQ(throughFifo(d.path("i.exr"), [&] { brdfcl::writeExrRgb(d.path("i.exr"), 64, 32, img); }),
            regularBytes([&](const std::string& p) { brdfcl::writeExrRgb(p, 64, 32, img); }, "i.exr"));
  EXPECT_EQ(d.list(), (std::vector<std::string>{"i.exr", "r.npy"}));
}

// ---- "-" is stdout ----

TEST(OutputFiles, DashWritesEveryFormatToStdout) {
  const auto rgb = someRows(3000);
  EXPECT_EQ(captureStdout([&] { brdfcl::writeResults("-", rgb); }),
            regularBytes([&](const std::string& p) { brdfcl::writeResults(p, rgb); }, "r.csv"));
  const std::vector<float> img = someRows(16 * 8);
  EXPECT_EQ(captureStdout([&] { brdfcl::writePng("-", 16, 8, img); }),
            regularBytes([&](const std::string& p) { brdfcl::writePng(p, 16, 8, img); }, "i.png"));
  EXPECT_EQ(captureStdout([&] { brdfcl::writeExrRgb("-", 16, 8, img); }),
            regularBytes([&](const std::string& p) { brdfcl::writeExrRgb(p, 16, 8, img); }, "i.exr"));
  const auto lut = smallLut(2);
  EXPECT_EQ(captureStdout([&] { brdfcl::writeLut(lut, "-"); }),
            regularBytes([&](const std::string& p) { brdfcl::writeLut(lut, p); }, "l.csv"));
}

TEST(OutputFiles, CliEvalAndLutWriteToStdout) {
  ScratchDir d("out-cli-dash");
  writeFile(d.path("m.json"), kMaterials);
  writeFile(d.path("s.csv"), kSamples);
  const RunResult file = runCli({"eval", "--materials", "m.json", "--samples", "s.csv", "--out", "r.csv"}, d);
  ASSERT_EQ(file.status, 0) << file.describe();
  const RunResult dash = runCli({"eval", "--materials", "m.json", "--samples", "s.csv", "--out", "-"}, d);
  ASSERT_EQ(dash.status, 0) << dash.describe();
  EXPECT_EQ(dash.out, slurp(d.path("r.csv")));
  // /dev/stdout is a /proc link to the open stdout: written in place, not replaced.
  const RunResult devStdout =
      runCli({"eval", "--materials", "m.json", "--samples", "s.csv", "--out", "/dev/stdout"}, d);
  ASSERT_EQ(devStdout.status, 0) << devStdout.describe();
  EXPECT_EQ(devStdout.out, dash.out);
  EXPECT_EQ(d.list(), (std::vector<std::string>{"m.json", "r.csv", "s.csv"}));

  const RunResult lutFile = runCli({"lut", "--kind", "ggx-dfg", "--size", "8", "--out", "l.csv"}, d);
  ASSERT_EQ(lutFile.status, 0) << lutFile.describe();
  const RunResult lutDash = runCli({"lut", "--kind", "ggx-dfg", "--size", "8", "--out", "-"}, d);
  ASSERT_EQ(lutDash.status, 0) << lutDash.describe();
  EXPECT_EQ(lutDash.out, slurp(d.path("l.csv")));
}

// ---- refusals ----

TEST(OutputFiles, DirectoryIsRefusedByEveryWriter) {
  ScratchDir d("out-dir");
  fs::create_directory(d.path("out.csv"));
  const std::string p = d.path("out.csv"), tail = "': it is a directory; name a file inside it";
  EXPECT_EQ(errorOf([&] { brdfcl::writeResults(p, {1, 2, 3}); }), "cannot write '" + p + tail);
  EXPECT_EQ(errorOf([&] { brdfcl::writePng(p, 1, 1, {1, 2, 3}); }), "cannot write '" + p + tail);
  EXPECT_EQ(errorOf([&] { brdfcl::writeLut(smallLut(1), p); }), "cannot write '" + p + tail);
  EXPECT_EQ(errorOf([&] { brdfcl::checkOutputPath("--out", p); }),
            "--out '" + p + "': cannot write: it is a directory; name a file inside it");
  // A link to a directory is the directory.
  fs::create_directory_symlink("out.csv", d.path("link.csv"));
  EXPECT_EQ(errorOf([&] { brdfcl::writeResults(d.path("link.csv"), {1, 2, 3}); }),
            "cannot write '" + d.path("link.csv") + tail);
  EXPECT_TRUE(fs::is_empty(p));

  writeFile(d.path("m.json"), kMaterials);
  writeFile(d.path("s.csv"), kSamples);
  const RunResult r = runCli({"eval", "--materials", "m.json", "--samples", "s.csv", "--out", "out.csv"}, d);
  EXPECT_EQ(r.status, 2) << r.describe();
  EXPECT_EQ(r.errorLines(), (std::vector<std::string>{"brdfcl: --out 'out.csv': cannot write: it is a directory; "
                                                      "name a file inside it"}));
  EXPECT_TRUE(fs::is_empty(p));
  EXPECT_FALSE(hasTemporary(d));
}

// What the commands ask before choosing a format by extension: the targets written in place.
TEST(OutputFiles, StreamTargetsAreStdoutFifosAndDevicesOnly) {
  ScratchDir d("out-stream");
  ASSERT_EQ(::mkfifo(d.path("f").c_str(), 0600), 0);
  std::ofstream(d.path("r.png")) << "x";
  EXPECT_TRUE(brdfcl::detail::isStreamTarget("-"));
  EXPECT_TRUE(brdfcl::detail::isStreamTarget("/dev/stdout"));
  EXPECT_TRUE(brdfcl::detail::isStreamTarget("/dev/null"));
  EXPECT_TRUE(brdfcl::detail::isStreamTarget(d.path("f")));
  EXPECT_FALSE(brdfcl::detail::isStreamTarget(d.path("r.png")));
  EXPECT_FALSE(brdfcl::detail::isStreamTarget(d.path("missing.png")));
  EXPECT_FALSE(brdfcl::detail::isStreamTarget(d.dir()));
}

TEST(OutputFiles, CheckOutputPathAcceptsDashFifosAndLinks) {
  ScratchDir d("out-check");
  EXPECT_NO_THROW(brdfcl::checkOutputPath("--out", "-"));
  ASSERT_EQ(::mkfifo(d.path("f").c_str(), 0600), 0);
  EXPECT_NO_THROW(brdfcl::checkOutputPath("--out", d.path("f")));
  EXPECT_NO_THROW(brdfcl::checkResultsPath("--out", d.path("f")));  // extensionless stream: CSV
  EXPECT_NO_THROW(brdfcl::checkOutputPath("--out", "/dev/null"));
  fs::create_directory(d.path("sub"));
  fs::create_symlink("sub/x.csv", d.path("l.csv"));
  EXPECT_NO_THROW(brdfcl::checkResultsPath("--out", d.path("l.csv")));
  // The link's target folder is the one that must exist.
  fs::create_symlink("missing/x.csv", d.path("bad.csv"));
  EXPECT_EQ(errorOf([&] { brdfcl::checkOutputPath("--out", d.path("bad.csv")); }),
            "--out '" + d.path("bad.csv") + "': cannot write: No such file or directory");
}

TEST(OutputFiles, CheckOutputPathWithExtensionsRefusesOthers) {
  ScratchDir d("out-check-ext");
  EXPECT_EQ(errorOf([&] { brdfcl::checkOutputPath("--out", d.path("img.jpg"), {".png"}); }),
            "--out '" + d.path("img.jpg") + "': cannot write: unknown extension; use .png or -");
  EXPECT_EQ(errorOf([&] { brdfcl::checkOutputPath("--exr", d.path("img"), {".exr"}); }),
            "--exr '" + d.path("img") + "': cannot write: unknown extension; use .exr or -");
  EXPECT_NO_THROW(brdfcl::checkOutputPath("--out", d.path("img.PNG"), {".png"}));
  EXPECT_NO_THROW(brdfcl::checkOutputPath("--out", "-", {".png"}));
  EXPECT_NO_THROW(brdfcl::checkOutputPath("--out", "/dev/null", {".png"}));
  // The path's own extension counts, not its link target's.
  fs::create_symlink("x.bin", d.path("l.png"));
  EXPECT_NO_THROW(brdfcl::checkOutputPath("--out", d.path("l.png"), {".png"}));
  EXPECT_TRUE(d.list() == std::vector<std::string>{"l.png"});
}

TEST(OutputFiles, UnknownResultsExtensionIsRefusedBeforeAnyWork) {
  ScratchDir d("out-ext");
  for (const char* name : {"o.exr", "o.json", "o"}) {
    const std::string p = d.path(name);
    EXPECT_EQ(errorOf([&] { brdfcl::writeResults(p, {1, 2, 3}); }),
              "cannot write '" + p + "': unknown extension; use .csv or .npy (- writes CSV to stdout)");
    EXPECT_EQ(errorOf([&] { brdfcl::checkResultsPath("--out", p); }),
              "--out '" + p + "': cannot write: unknown extension; use .csv or .npy (- writes CSV to stdout)");
  }
  EXPECT_TRUE(d.list().empty());
  EXPECT_NO_THROW(brdfcl::checkResultsPath("--out", d.path("x.CSV")));
  EXPECT_NO_THROW(brdfcl::checkResultsPath("--out", d.path("x.Npy")));

  writeFile(d.path("m.json"), kMaterials);
  writeFile(d.path("s.csv"), kSamples);
  // --device names no device: only an error raised before the device is opened passes here.
  const RunResult r =
      runCli({"eval", "--materials", "m.json", "--samples", "s.csv", "--out", "o.exr", "--device", "no-such"}, d);
  EXPECT_EQ(r.status, 2) << r.describe();
  EXPECT_EQ(r.errorLines(), (std::vector<std::string>{"brdfcl: --out 'o.exr': cannot write: unknown extension; "
                                                      "use .csv or .npy (- writes CSV to stdout)"}));
  EXPECT_EQ(d.list(), (std::vector<std::string>{"m.json", "s.csv"}));
}

// ---- LUT as .npy ----

TEST(OutputFiles, LutNpyHasTheTexelLayout) {
  ScratchDir d("out-lut-npy");
  for (int channels : {1, 2}) {
    const auto lut = smallLut(channels);
    const std::string p = d.path("l" + std::to_string(channels) + ".NPY");
    brdfcl::writeLut(lut, p);
    const std::string bytes = slurp(p);
    ASSERT_EQ(bytes.size(), 128 + lut.values.size() * 4);
    EXPECT_EQ(bytes.substr(0, 6), "\x93NUMPY");
    const std::string shape = channels == 1 ? "'shape': (3, 3), }" : "'shape': (3, 3, 2), }";
    EXPECT_NE(bytes.find("{'descr': '<f4', 'fortran_order': False, " + shape), std::string::npos) << bytes.substr(0, 128);
    std::vector<float> v(lut.values.size());
    std::memcpy(v.data(), bytes.data() + 128, v.size() * 4);
    // Row-major (j, i, c): element [j][i][c] is lut.at(i, j, c).
    for (std::size_t j = 0; j < 3; ++j)
      for (std::size_t i = 0; i < 3; ++i)
        for (int c = 0; c < channels; ++c) EXPECT_EQ(v[(j * 3 + i) * channels + c], lut.at(i, j, c));
  }
  EXPECT_NO_THROW(brdfcl::checkLutPath(d.path("x.npy")));
  EXPECT_FALSE(hasTemporary(d));
}

// ---- signals and stale temporaries ----

// Starts the CLI with default signal dispositions (a test runner may ignore SIGINT) and its
// output in `d`.
pid_t spawnCli(const std::vector<std::string>& args, const ScratchDir& d, const std::string& logDir) {
  std::vector<std::string> argv{BRDFCL_CLI_PATH};
  argv.insert(argv.end(), args.begin(), args.end());
  std::vector<char*> cargs;
  for (auto& a : argv) cargs.push_back(a.data());
  cargs.push_back(nullptr);
  const std::string cwd = d.dir(), out = logDir + "/stdout", err = logDir + "/stderr";
  const pid_t pid = ::fork();
  if (pid == 0) {
    for (const int s : {SIGINT, SIGTERM, SIGHUP}) ::signal(s, SIG_DFL);
    sigset_t none;
    sigemptyset(&none);
    ::sigprocmask(SIG_SETMASK, &none, nullptr);
    const int o = ::open(out.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
    const int e = ::open(err.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
    if (::chdir(cwd.c_str()) != 0 || o < 0 || e < 0 || ::dup2(o, 1) < 0 || ::dup2(e, 2) < 0) ::_exit(126);
    ::execv(cargs[0], cargs.data());
    ::_exit(127);
  }
  return pid;
}

// A grid of 400 materials x 50000 directions: 20 million result rows, far more than the
// seconds the test waits, from small inputs.
void writeBigGrid(const ScratchDir& d) {
  std::string m = R"({"materials": [)";
  for (int i = 0; i < 400; ++i)
    m += std::string(i ? "," : "") + R"({"pbrMetallicRoughness": {"roughnessFactor": )" +
         std::to_string(0.1 + 0.002 * i) + "}}";
  writeFile(d.path("m.json"), m + "]}");
  std::string s = "Lx,Ly,Lz,Vx,Vy,Vz\n";
  for (int i = 0; i < 50000; ++i) s += std::to_string((i % 97) / 200.0) + ",0.1,1,0," + std::to_string((i % 89) / 200.0) + ",1\n";
  writeFile(d.path("s.csv"), s);
}

void expectSignalRemovesTemporary(int signo) {
  ScratchDir d("out-sig"), logs("out-sig-logs");
  writeBigGrid(d);
  const pid_t pid = spawnCli({"eval", "--grid", "--materials", "m.json", "--samples", "s.csv", "--out", "big.csv"}, d,
                             logs.dir());
  ASSERT_GT(pid, 0);
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(120);
  bool seen = false;
  int status = 0;
  while (!seen && std::chrono::steady_clock::now() < deadline) {
    seen = hasTemporary(d);
    if (!seen && ::waitpid(pid, &status, WNOHANG) == pid) FAIL() << "the CLI ended before writing: " << slurp(logs.path("stderr"));
    if (!seen) std::this_thread::sleep_for(std::chrono::milliseconds(2));
  }
  if (!seen) ::kill(pid, SIGKILL);
  ::kill(pid, signo);
  ASSERT_EQ(::waitpid(pid, &status, 0), pid);
  ASSERT_TRUE(seen) << "no temporary appeared within the deadline";
  ASSERT_TRUE(WIFEXITED(status)) << "killed by signal " << (WIFSIGNALED(status) ? WTERMSIG(status) : 0);
  EXPECT_EQ(WEXITSTATUS(status), 128 + signo) << slurp(logs.path("stderr"));
  EXPECT_EQ(d.list(), (std::vector<std::string>{"m.json", "s.csv"}));
}

TEST(OutputFiles, SigintRemovesTemporariesAndExits130) { expectSignalRemovesTemporary(SIGINT); }
TEST(OutputFiles, SigtermRemovesTemporariesAndExits143) { expectSignalRemovesTemporary(SIGTERM); }
TEST(OutputFiles, SighupRemovesTemporariesAndExits129) { expectSignalRemovesTemporary(SIGHUP); }

// Names in the form ".<name>.tmp.<pid>.<n>" are users' files to the sweep, whatever their pid:
// it removes only exact temporaries' names (test_output_hostile.cpp TemporarySweep).
TEST(OutputFiles, NamesThatOnlyLookLikeTemporariesAreKept) {
  ScratchDir d("out-stale");
  const std::string stale = ".x.csv.tmp." + std::to_string(deadPid()) + ".0";
  const std::string ours = ".x.csv.tmp." + std::to_string(::getpid()) + ".0";
  const std::string parent = ".z.png.tmp." + std::to_string(::getppid()) + ".7";
  for (const auto& name : {stale, ours, parent, std::string(".not.ours.tmp.x.0")}) writeFile(d.path(name), "left");
  brdfcl::writeResults(d.path("y.csv"), {1, 2, 3});
  std::vector<std::string> expected{".not.ours.tmp.x.0", stale, ours, parent, "y.csv"};
  std::sort(expected.begin(), expected.end());
  EXPECT_EQ(d.list(), expected);
}

}  // namespace
