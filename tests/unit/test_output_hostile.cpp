// Outputs in unfriendly surroundings: a replaced file keeps its mode and owner, the stale-temporary
// sweep spares what is not provably its own, an output that is an input or another output is
// refused, and a full disk or a file size limit (one process or under mpirun) fails cleanly.
#include <fcntl.h>
#include <gtest/gtest.h>
#include <signal.h>
#include <sys/mount.h>
#include <sys/resource.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <functional>
#include <map>
#include <random>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include "brdfcl/error.hpp"
#include "brdfcl/image.hpp"
#include "brdfcl/io.hpp"
#include "gltf_builder.hpp"
#include "host/src/io/temporaries.hpp"
#include "process.hpp"
#include "support.hpp"

namespace fs = std::filesystem;
using brdfcl::test::RunResult;
using brdfcl::test::ScratchDir;
using brdfcl::test::deadPid;
using brdfcl::test::writeFile;
using brdfcl::test::errorOf;
using brdfcl::test::slurp;

namespace {

mode_t modeOf(const std::string& p) {
  struct stat st {};
  EXPECT_EQ(::stat(p.c_str(), &st), 0) << p;
  return st.st_mode & 07777;
}

bool hasTemporary(const std::vector<std::string>& names) {
  for (const auto& n : names)
    if (n.find(".tmp.") != std::string::npos) return true;
  return false;
}

// The umask for one scope (process-wide: the writes under test run on this thread).
class Umask {
 public:
  explicit Umask(mode_t m) : old_(::umask(m)) {}
  ~Umask() { ::umask(old_); }

 private:
  mode_t old_;
};

// ---- modes and owners ----

// The three ways a file is written: streamed results, a whole buffer (PNG), a temporary handed to
// a writer (EXR).
void writeEachKind(const ScratchDir& d) {
  brdfcl::writeResults(d.path("r.csv"), {1, 2, 3});
  brdfcl::writePng(d.path("p.png"), 1, 1, {0.5f, 0.5f, 0.5f});
  brdfcl::writeExrRgb(d.path("e.exr"), 1, 1, {0.5f, 0.5f, 0.5f});
}

TEST(OutputModes, ReplacedFileKeepsItsMode) {
  ScratchDir d("hostile-mode");
  const Umask umask(022);
  for (const char* n : {"r.csv", "p.png", "e.exr"}) {
    writeFile(d.path(n), "old");
    ASSERT_EQ(::chmod(d.path(n).c_str(), 0600), 0);
  }
  writeFile(d.path("wide.csv"), "old");
  ASSERT_EQ(::chmod(d.path("wide.csv").c_str(), 0664), 0);
  writeEachKind(d);
  brdfcl::writeResults(d.path("wide.csv"), {1, 2, 3});
  for (const char* n : {"r.csv", "p.png", "e.exr"}) {
    EXPECT_EQ(modeOf(d.path(n)), 0600u) << n;
    EXPECT_NE(slurp(d.path(n)), "old") << n;
  }
  EXPECT_EQ(modeOf(d.path("wide.csv")), 0664u);
}

TEST(OutputModes, NewFileFollowsTheUmask) {
  for (const mode_t mask : {mode_t(022), mode_t(077)}) {
    ScratchDir d("hostile-umask");
    const Umask umask(mask);
    writeEachKind(d);
    for (const char* n : {"r.csv", "p.png", "e.exr"}) EXPECT_EQ(modeOf(d.path(n)), 0666u & ~mask) << n << " umask " << mask;
  }
}

// Through a symlink the target is replaced; the link stays a link and the target keeps its mode.
TEST(OutputModes, ReplacedFileBehindASymlinkKeepsItsMode) {
  ScratchDir d("hostile-mode-link");
  writeFile(d.path("target.csv"), "old");
  ASSERT_EQ(::chmod(d.path("target.csv").c_str(), 0640), 0);
  fs::create_symlink("target.csv", d.path("link.csv"));
  brdfcl::writeResults(d.path("link.csv"), {1, 2, 3});
  EXPECT_TRUE(fs::is_symlink(d.path("link.csv")));
  EXPECT_EQ(modeOf(d.path("target.csv")), 0640u);
}

TEST(OutputModes, ReplacedFileKeepsItsOwnerWherePermitted) {
  if (::geteuid() != 0) GTEST_SKIP() << "giving a file to another user needs root (CI runs as root)";
  ScratchDir d("hostile-owner");
  writeFile(d.path("r.csv"), "old");
  writeFile(d.path("e.exr"), "old");
  for (const char* n : {"r.csv", "e.exr"}) {
    ASSERT_EQ(::chown(d.path(n).c_str(), 65534, 65534), 0);
    ASSERT_EQ(::chmod(d.path(n).c_str(), 0604), 0);
  }
  brdfcl::writeResults(d.path("r.csv"), {1, 2, 3});
  brdfcl::writeExrRgb(d.path("e.exr"), 1, 1, {0.5f, 0.5f, 0.5f});
  for (const char* n : {"r.csv", "e.exr"}) {
    struct stat st {};
    ASSERT_EQ(::stat(d.path(n).c_str(), &st), 0);
    EXPECT_EQ(st.st_uid, 65534u) << n;
    EXPECT_EQ(st.st_gid, 65534u) << n;
    EXPECT_EQ(st.st_mode & 07777, 0604u) << n;
  }
}

// ---- temporaries' names and the sweep ----

void makeOld(const std::string& p) {
  struct timespec times[2];
  ::clock_gettime(CLOCK_REALTIME, &times[0]);
  times[0].tv_sec -= 2 * 3600;
  times[1] = times[0];
  ASSERT_EQ(::utimensat(AT_FDCWD, p.c_str(), times, AT_SYMLINK_NOFOLLOW), 0) << p;
}

TEST(TemporaryNames, HoldTheHostSafelyWithinNameMax) {
  using brdfcl::detail::TemporaryOwner;
  std::string odd;
  for (int c = 1; c < 256; ++c) odd += char(c);  // slashes, dots, control and high bytes
  for (const std::string& host : {std::string("node-7.cluster.example"), odd, std::string(255, '.'),
                                  std::string("a/../b"), std::string("")}) {
    TemporaryOwner owner;
    owner.host = brdfcl::detail::encodeHostName(host);
    owner.pidNamespace = 18446744073709551615ull;
    owner.pid = 2147483647;
    const std::string name = brdfcl::detail::temporaryName(owner);
    EXPECT_LE(name.size(), 255u) << name;
    EXPECT_EQ(name.find('/'), std::string::npos) << name;
    EXPECT_EQ(name.rfind(".brdfcl.tmp.", 0), 0u) << name;
    TemporaryOwner back;
    if (host.empty()) continue;  // gethostname never gives "", which encodes to nothing
    ASSERT_TRUE(brdfcl::detail::parseTemporaryName(name, back)) << name;
    EXPECT_EQ(back.host, owner.host);
    EXPECT_EQ(back.pidNamespace, owner.pidNamespace);
    EXPECT_EQ(back.pid, owner.pid);
  }
  EXPECT_NE(brdfcl::detail::encodeHostName("a.b"), brdfcl::detail::encodeHostName("a_2eb.x"));
  // Only exact names: users' files that merely look temporary are no temporaries.
  TemporaryOwner o;
  for (const char* name : {".notes.tmp.999999.1", ".x.csv.tmp.123.0", ".brdfcl.tmp.host.0.12.0123456789abcdef.csv",
                           ".brdfcl.tmp.host.0.12.0123456789ABCDEF", ".brdfcl.tmp.host.0.012.0123456789abcdef",
                           ".brdfcl.tmp.ho.st.0.12.0123456789abcdef", ".brdfcl.tmp.h_zz.0.12.0123456789abcdef",
                           ".brdfcl.tmp..0.12.0123456789abcdef", "brdfcl.tmp.host.0.12.0123456789abcdef"})
    EXPECT_FALSE(brdfcl::detail::parseTemporaryName(name, o)) << name;
  EXPECT_TRUE(brdfcl::detail::parseTemporaryName(".brdfcl.tmp.host.0.12.0123456789abcdef", o));
}

// One test for both halves, so that it fails without the sweep: only the old temporary of a dead
// process of this host goes.
TEST(TemporarySweep, RemovesOnlyOldTemporariesOfDeadProcessesOfThisHost) {
  using brdfcl::detail::TemporaryOwner;
  ScratchDir d("hostile-sweep");
  const pid_t dead = deadPid();
  TemporaryOwner mine = brdfcl::detail::thisProcess();
  mine.pid = dead;
  TemporaryOwner foreign = mine;
  foreign.host = brdfcl::detail::encodeHostName("another-node.example");
  TemporaryOwner otherNamespace = mine;
  otherNamespace.pidNamespace = mine.pidNamespace + 1;
  const std::string stale = brdfcl::detail::temporaryName(mine);
  const std::string young = brdfcl::detail::temporaryName(mine);
  const std::string otherHost = brdfcl::detail::temporaryName(foreign);
  const std::string container = brdfcl::detail::temporaryName(otherNamespace);
  TemporaryOwner live = brdfcl::detail::thisProcess();
  live.pid = ::getppid();
  const std::string parent = brdfcl::detail::temporaryName(live);
  const std::vector<std::string> kept{".notes.tmp.999999.1", ".x.csv.tmp." + std::to_string(dead) + ".0", young,
                                      otherHost, container, parent};
  for (const auto& n : kept) writeFile(d.path(n), "left");
  writeFile(d.path(stale), "left");
  for (const auto& n : kept)
    if (n != young) makeOld(d.path(n));
  makeOld(d.path(stale));
  brdfcl::writeResults(d.path("y.csv"), {1, 2, 3});
  std::vector<std::string> expected = kept;
  expected.push_back("y.csv");
  std::sort(expected.begin(), expected.end());
  EXPECT_EQ(d.list(), expected);
}

// ---- an output that is an input, or another output ----

// A glTF asset of one quad, which `gbuffer --gltf` ray-casts on the host (no OpenCL device).
std::string writeQuadAsset(const ScratchDir& d) {
  brdfcl::test::GltfBuilder b;
  const int material = b.addMaterial({{"pbrMetallicRoughness", {{"roughnessFactor", 0.5}}}});
  const int quad = b.addTriangles({-1, -1, 0, 1, -1, 0, 1, 1, 0, -1, 1, 0}, {0, 1, 2, 0, 2, 3}, material,
                                  {0, 0, 1, 0, 0, 1, 0, 0, 1, 0, 0, 1});
  b.addScene({b.addMeshNode(b.addMesh({quad}))});
  return b.write(d.dir(), "a.gltf");
}

RunResult cli(const std::vector<std::string>& args, const ScratchDir& d, const ScratchDir& logs) {
  std::vector<std::string> argv{BRDFCL_CLI_PATH};
  argv.insert(argv.end(), args.begin(), args.end());
  return brdfcl::test::runProcess(argv, logs.dir(), d.dir());
}

struct Refusal {
  std::vector<std::string> args;
  std::string message;
};

TEST(SameFile, EveryCommandRefusesAnOutputThatIsAnInputOrAnotherOutput) {
  ScratchDir d("hostile-same"), logs("hostile-same-logs");
  writeFile(d.path("m.json"), R"({"materials": [{"pbrMetallicRoughness": {"roughnessFactor": 0.5}}]})");
  writeFile(d.path("s.csv"), "material,Lx,Ly,Lz,Vx,Vy,Vz\n0,0,0,1,0,0,1\n");
  writeFile(d.path("g.exr"), "a G-buffer");
  writeFile(d.path("scene.json"), R"({"lights": []})");
  writeFile(d.path("env.exr"), "an environment");
  writeFile(d.path("b.exr"), "an image");
  writeFile(d.path("r.png"), "a picture");
  writeQuadAsset(d);
  fs::create_symlink("s.csv", d.path("link.csv"));
  fs::create_hard_link(d.path("s.csv"), d.path("hard.csv"));
  fs::create_symlink("m.json", d.path("m.csv"));
  fs::create_symlink("new.exr", d.path("dangling.png"));
  fs::create_hard_link(d.path("r.png"), d.path("hard.exr"));
  fs::create_symlink("a.gltf", d.path("asset.exr"));
  fs::create_symlink("g.exr", d.path("pic.png"));
  const std::string refuse = "; write the output elsewhere", twice = "; give each output its own file";
  const std::vector<Refusal> cases = {
      {{"eval", "--materials", "m.json", "--samples", "s.csv", "--out", "s.csv"},
       "--out 's.csv' is the same file as --samples 's.csv'" + refuse},
      {{"eval", "--materials", "m.json", "--samples", "s.csv", "--out", "link.csv"},
       "--out 'link.csv' is the same file as --samples 's.csv'" + refuse},
      {{"eval", "--materials", "m.json", "--samples", "s.csv", "--out", "hard.csv"},
       "--out 'hard.csv' is the same file as --samples 's.csv'" + refuse},
      {{"eval", "--materials", "m.json", "--samples", "s.csv", "--out", "m.csv"},
       "--out 'm.csv' is the same file as --materials 'm.json'" + refuse},
      {{"shade", "--gbuffer", "g.exr", "--scene", "scene.json", "--out", "g.exr"},
       "--out 'g.exr' is the same file as --gbuffer 'g.exr'" + refuse},
      {{"shade", "--gbuffer", "g.exr", "--scene", "scene.json", "--out", "new.exr", "--png", "dangling.png"},
       "--png 'dangling.png' is the same file as --out 'new.exr'" + twice},
      {{"render", "--out", "x.exr", "--gbuffer", "x.exr"}, "--gbuffer 'x.exr' is the same file as --out 'x.exr'" + twice},
      {{"render", "--out", "r.png", "--gbuffer", "hard.exr"}, "--gbuffer 'hard.exr' is the same file as --out 'r.png'" + twice},
      {{"render", "--gltf", "a.gltf", "--out", "o.png", "--exr", "asset.exr"},
       "--exr 'asset.exr' is the same file as --gltf 'a.gltf'" + refuse},
      {{"render", "--environment", "env.exr", "--out", "env.exr"},
       "--out 'env.exr' is the same file as --environment 'env.exr'" + refuse},
      {{"render", "--lights", "scene.json", "--out", "o.png", "--exr", "./sub/../g.exr", "--gbuffer", "g.exr"},
       "--gbuffer 'g.exr' is the same file as --exr './sub/../g.exr'" + twice},
      {{"gbuffer", "--gltf", "a.gltf", "--out", "asset.exr"}, "--out 'asset.exr' is the same file as --gltf 'a.gltf'" + refuse},
      {{"diff", "g.exr", "b.exr", "--out", "pic.png"}, "--out 'pic.png' is the same file as A 'g.exr'" + refuse},
  };
  fs::create_directory(d.path("sub"));
  const auto before = d.list();
  std::map<std::string, std::string> contents;
  for (const auto& n : before)
    if (fs::is_regular_file(d.path(n))) contents[n] = slurp(d.path(n));
  for (const auto& c : cases) {
    const RunResult r = cli(c.args, d, logs);
    EXPECT_EQ(r.status, 2) << c.args[0] << " " << c.message << "\n" << r.describe();
    EXPECT_EQ(r.err, "brdfcl: " + c.message + "\n") << r.describe();
  }
  EXPECT_EQ(d.list(), before) << "a refused run left or removed files";
  for (const auto& [n, content] : contents) EXPECT_TRUE(slurp(d.path(n)) == content) << "a refused run changed " << n;
}

TEST(SameFile, StreamsAndDistinctFilesAreNotRefused) {
  ScratchDir d("hostile-distinct");
  writeFile(d.path("in.csv"), "x");
  EXPECT_NO_THROW(brdfcl::checkDistinctFiles({{"--out", "/dev/null", true}, {"--exr", "/dev/null", true}}));
  EXPECT_NO_THROW(brdfcl::checkDistinctFiles({{"--samples", "-", false}, {"--out", "-", true}}));
  EXPECT_NO_THROW(brdfcl::checkDistinctFiles({{"--samples", d.path("in.csv"), false}, {"--out", d.path("out.csv"), true},
                                              {"--png", "", true}, {"--exr", d.path("out.exr"), true}}));
  // Two inputs may be one file (diff a.exr a.exr).
  EXPECT_NO_THROW(brdfcl::checkDistinctFiles({{"A", d.path("in.csv"), false}, {"B", d.path("in.csv"), false}}));
  EXPECT_EQ(errorOf([&] {
              brdfcl::checkDistinctFiles({{"--out", d.path("n.exr"), true}, {"--exr", d.dir() + "/./n.exr", true}});
            }),
            "--exr '" + d.dir() + "/./n.exr' is the same file as --out '" + d.path("n.exr") +
                "'; give each output its own file");
}

// ---- full disks and file size limits ----

struct Limits {
  rlim_t fileSize = RLIM_INFINITY;  // RLIMIT_FSIZE of the child
  std::map<std::string, std::string> env;
  std::string cwd;
  std::chrono::seconds timeout{300};
};

// The child with default SIGXFSZ and SIGPIPE (whatever this process has), its limit set before
// exec, its stdout and stderr in `logDir`.
RunResult runLimited(std::vector<std::string> argv, const std::string& logDir, const Limits& l) {
  std::vector<std::string> envStrings;
  for (char** e = environ; *e; ++e) {
    const std::string kv = *e;
    if (!l.env.count(kv.substr(0, kv.find('=')))) envStrings.push_back(kv);
  }
  for (const auto& [k, v] : l.env) envStrings.push_back(k + "=" + v);
  std::vector<char*> args, envp;
  for (auto& a : argv) args.push_back(a.data());
  args.push_back(nullptr);
  for (auto& e : envStrings) envp.push_back(e.data());
  envp.push_back(nullptr);
  const std::string outPath = logDir + "/stdout", errPath = logDir + "/stderr";
  struct rlimit limit {};
  ::getrlimit(RLIMIT_FSIZE, &limit);
  limit.rlim_cur = l.fileSize;
  const pid_t pid = ::fork();
  if (pid < 0) throw std::runtime_error("fork failed");
  if (pid == 0) {
    ::signal(SIGXFSZ, SIG_DFL);
    ::signal(SIGPIPE, SIG_DFL);
    const int in = ::open("/dev/null", O_RDONLY);
    const int out = ::open(outPath.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
    const int err = ::open(errPath.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
    if (in < 0 || out < 0 || err < 0 || ::dup2(in, 0) < 0 || ::dup2(out, 1) < 0 || ::dup2(err, 2) < 0) ::_exit(126);
    if (!l.cwd.empty() && ::chdir(l.cwd.c_str()) != 0) ::_exit(126);
    if (::setrlimit(RLIMIT_FSIZE, &limit) != 0) ::_exit(126);
    ::execve(args[0], args.data(), envp.data());
    ::_exit(127);
  }
  const auto deadline = std::chrono::steady_clock::now() + l.timeout;
  int status = 0;
  for (;;) {
    const pid_t w = ::waitpid(pid, &status, WNOHANG);
    if (w == pid) break;
    if (std::chrono::steady_clock::now() > deadline) {
      ::kill(pid, SIGKILL);
      ::waitpid(pid, &status, 0);
      throw std::runtime_error(argv[0] + " did not finish in time");
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
  }
  RunResult r;
  r.status = WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
  r.out = slurp(outPath);
  r.err = slurp(errPath);
  return r;
}

// OpenEXR writes through a C++ stream: under `ulimit -f` the write must fail with EFBIG and take
// the ordinary error path (exit 2, old file kept, no temporary), not die of SIGXFSZ.
TEST(FileSizeLimit, ExrWriterExitsTwoAndLeavesNoTemporary) {
  ScratchDir d("hostile-fsize"), logs("hostile-fsize-logs");
  writeQuadAsset(d);
  writeFile(d.path("g.exr"), "old");
  Limits l;
  l.fileSize = 4096;
  l.cwd = d.dir();
  const RunResult r = runLimited({BRDFCL_CLI_PATH, "gbuffer", "--gltf", "a.gltf", "--size", "128x128", "--out", "g.exr"},
                                 logs.dir(), l);
  EXPECT_EQ(r.status, 2) << r.describe();
  EXPECT_EQ(r.errorLines().size(), 1u) << r.describe();
  EXPECT_EQ(r.err.rfind("brdfcl: cannot write 'g.exr': ", 0), 0u) << r.describe();
  EXPECT_EQ(slurp(d.path("g.exr")), "old");
  EXPECT_EQ(d.list(), (std::vector<std::string>{"a.gltf", "g.exr"}));
}

// A spooled EXR streamed to stdout: a reader that stops early ends the run, and the spool in the
// temp directory goes with it.
TEST(SpooledOutput, ClosedPipeLeavesNoSpool) {
  ScratchDir d("hostile-pipe"), spool("hostile-pipe-tmp");
  writeQuadAsset(d);
  int fds[2];
  ASSERT_EQ(::pipe(fds), 0);
  std::string cli = BRDFCL_CLI_PATH, tmpdir = "TMPDIR=" + spool.dir();
  std::vector<char*> args{cli.data()};
  std::vector<std::string> rest{"gbuffer", "--gltf", "a.gltf", "--size", "512x512", "--out", "-"};
  for (auto& a : rest) args.push_back(a.data());
  args.push_back(nullptr);
  std::vector<std::string> envStrings;
  for (char** e = environ; *e; ++e)
    if (std::strncmp(*e, "TMPDIR=", 7) != 0) envStrings.push_back(*e);
  envStrings.push_back(tmpdir);
  std::vector<char*> envp;
  for (auto& e : envStrings) envp.push_back(e.data());
  envp.push_back(nullptr);
  const std::string cwd = d.dir();
  const pid_t pid = ::fork();
  ASSERT_GE(pid, 0);
  if (pid == 0) {
    ::signal(SIGPIPE, SIG_DFL);
    const int null = ::open("/dev/null", O_RDWR);
    if (null < 0 || ::dup2(fds[1], 1) < 0 || ::dup2(null, 2) < 0 || ::dup2(null, 0) < 0 || ::chdir(cwd.c_str()) != 0)
      ::_exit(126);
    ::close(fds[0]);
    ::close(fds[1]);
    ::execve(args[0], args.data(), envp.data());
    ::_exit(127);
  }
  ::close(fds[1]);
  char head[16];
  const ssize_t got = ::read(fds[0], head, sizeof head);  // `head -c 16`
  ::close(fds[0]);
  int status = 0;
  ASSERT_EQ(::waitpid(pid, &status, 0), pid);
  ASSERT_EQ(got, ssize_t(sizeof head)) << "the CLI wrote nothing";
  EXPECT_EQ(std::string(head, 4), std::string("\x76\x2f\x31\x01", 4)) << "not an EXR";
  // Killed by SIGPIPE, or exiting 128 + SIGPIPE after its cleanup, or 2 where SIGPIPE is ignored.
  const int code = WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
  EXPECT_TRUE(code == 128 + SIGPIPE || code == 2) << "status " << code;
  EXPECT_EQ(spool.list(), std::vector<std::string>{}) << "the spool was left in TMPDIR";
  EXPECT_EQ(d.list(), std::vector<std::string>{"a.gltf"});
}

// ---- under mpirun ----

std::string findProgram(const std::string& name) {
  const char* path = std::getenv("PATH");
  std::stringstream dirs(path ? path : "");
  for (std::string dir; std::getline(dirs, dir, ':');) {
    const std::string candidate = (dir.empty() ? "." : dir) + "/" + name;
    if (::access(candidate.c_str(), X_OK) == 0) return candidate;
  }
  return "";
}

class MpiFullDisk : public ::testing::Test {
 protected:
  void SetUp() override {
    mpirun_ = findProgram("mpirun");
    if (mpirun_.empty()) GTEST_SKIP() << "mpirun is not on PATH; install openmpi-bin (make deps) to run the MPI tests";
    writeFile(dir_.path("m.json"), R"({"materials": [{"pbrMetallicRoughness": {"roughnessFactor": 0.5}},
      {"pbrMetallicRoughness": {"metallicFactor": 1, "roughnessFactor": 0.3}}]})");
    std::mt19937 rng(7);
    std::uniform_real_distribution<float> u(-1.0f, 1.0f), up(0.05f, 1.0f);
    std::ostringstream s;
    s.precision(9);
    s << "material,Lx,Ly,Lz,Vx,Vy,Vz\n";
    for (int i = 0; i < kRows; ++i)
      s << i % 2 << ',' << u(rng) << ',' << u(rng) << ',' << up(rng) << ',' << u(rng) << ',' << u(rng) << ','
        << up(rng) << '\n';
    writeFile(dir_.path("s.csv"), s.str());
  }

  // `args` under mpirun -n 3, each rank under RLIMIT_FSIZE `fileSize` (set by prlimit, so that
  // mpirun's own shared-memory files are not limited), its exit status in runs_/status.<rank>.
  // The wrapper itself exits 0: mpirun kills the other ranks when one exits non-zero, and every
  // rank's own status is what is checked.
  RunResult many(const std::vector<std::string>& args, rlim_t fileSize) const {
    std::vector<std::string> argv{mpirun_, "-q", "--oversubscribe"};
    if (::geteuid() == 0) argv.push_back("--allow-run-as-root");  // CI containers run as root
    const std::string limit =
        fileSize == RLIM_INFINITY ? "" : "\"" + prlimit_ + "\" --fsize=" + std::to_string(fileSize) + " ";
    argv.insert(argv.end(), {"-n", "3", "/bin/sh", "-c",
                             limit + "\"$0\" \"$@\"; echo $? > \"" + runs_.dir() + "/status.$OMPI_COMM_WORLD_RANK\"",
                             BRDFCL_CLI_PATH});
    argv.insert(argv.end(), args.begin(), args.end());
    Limits l;
    l.cwd = dir_.dir();
    l.env["OMPI_MCA_btl_vader_single_copy_mechanism"] = "none";
    if (const char* asan = std::getenv("ASAN_OPTIONS"); asan != nullptr)
      l.env["ASAN_OPTIONS"] = std::string(asan) + ":detect_leaks=0";
    for (int r = 0; r < 3; ++r) fs::remove(runs_.path("status." + std::to_string(r)));
    return runLimited(argv, runs_.dir(), l);
  }

  std::vector<std::string> rankStatuses() const {
    std::vector<std::string> s;
    for (int r = 0; r < 3; ++r) {
      std::string v = slurp(runs_.path("status." + std::to_string(r)));
      while (!v.empty() && v.back() == '\n') v.pop_back();
      s.push_back(v);
    }
    return s;
  }

  // A first run writes `out` (and compiles the kernels while no limit is in force); the second,
  // which cannot fit, must fail on every rank with one line and keep the first run's file.
  void expectCleanFailure(const std::string& out, const std::string& outDir, rlim_t fileSize) {
    const std::vector<std::string> args{"eval", "--materials", "m.json", "--samples", "s.csv", "--out", out};
    if (fileSize == RLIM_INFINITY) {
      writeFile(dir_.path(out), "the previous results\n");
    } else {
      const RunResult first = many(args, RLIM_INFINITY);
      ASSERT_EQ(rankStatuses(), (std::vector<std::string>{"0", "0", "0"})) << first.describe();
    }
    const std::string previous = slurp(dir_.path(out));
    const auto before = listOf(outDir);
    const RunResult r = many(args, fileSize);
    EXPECT_EQ(rankStatuses(), (std::vector<std::string>{"2", "2", "2"})) << r.describe();
    EXPECT_EQ(r.errorLines().size(), 1u) << r.describe();
    EXPECT_EQ(r.err.rfind("brdfcl: cannot write '" + out + "': ", 0), 0u) << r.describe();
    EXPECT_TRUE(slurp(dir_.path(out)) == previous) << "the previous " << out << " was replaced";
    EXPECT_EQ(listOf(outDir), before) << "a temporary was left";
    EXPECT_FALSE(hasTemporary(listOf(outDir)));
  }

  std::vector<std::string> listOf(const std::string& sub) const {
    std::vector<std::string> names;
    for (const auto& e : fs::directory_iterator(dir_.path(sub))) names.push_back(e.path().filename().string());
    std::sort(names.begin(), names.end());
    return names;
  }

  static constexpr int kRows = 60000;  // about 2.3 MB of CSV results, 0.7 MB of NPY
  std::string mpirun_, prlimit_ = findProgram("prlimit");
  ScratchDir dir_{"hostile-mpi"}, runs_{"hostile-mpi-runs"};
};

// RLIMIT_FSIZE below the whole file but above each rank's part: the shared file's writes fail
// (EFBIG) on the ranks that write past the limit, and MPI-IO reports them as short writes.
TEST_F(MpiFullDisk, FileSizeLimitFailsEveryRankAndKeepsTheOldFile) {
  if (prlimit_.empty()) GTEST_SKIP() << "prlimit (util-linux) is not on PATH";
  expectCleanFailure("m.csv", ".", 1200 << 10);
  expectCleanFailure("m.npy", ".", 400 << 10);
}

// A real full file system: a 512 KiB tmpfs, where mounting one is allowed (root with CAP_SYS_ADMIN).
TEST_F(MpiFullDisk, FullTmpfsFailsEveryRankAndKeepsTheOldFile) {
  const std::string full = dir_.path("full");
  fs::create_directory(full);
  if (::mount("tmpfs", full.c_str(), "tmpfs", 0, "size=512k") != 0)
    GTEST_SKIP() << "cannot mount a tmpfs here (" << std::strerror(errno)
                 << "); FileSizeLimitFailsEveryRankAndKeepsTheOldFile covers the same path";
  struct Unmount {
    std::string path;
    ~Unmount() { ::umount2(path.c_str(), MNT_DETACH); }
  } unmount{full};
  expectCleanFailure("full/m.csv", "full", RLIM_INFINITY);
  expectCleanFailure("full/m.npy", "full", RLIM_INFINITY);
}

}  // namespace
