// Test support for running built programs as a user would (stdin from /dev/null, stdout and
// stderr captured, a deadline, the child's peak resident memory) and for scratch directories
// that hold their inputs and outputs.
#pragma once
#include <fcntl.h>
#include <signal.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <chrono>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>
#include <stdexcept>
#include <string>
#include <thread>
#include <vector>

extern char** environ;

namespace brdfcl::test {

struct RunResult {
  int status = -1;  // exit code, or 128 + signal
  std::string out, err;
  long maxRssKiB = 0;  // the child's peak resident set

  // stderr without warnings: the error contract allows warnings before the one error line.
  std::vector<std::string> errorLines() const { return lines(false); }
  std::vector<std::string> warningLines() const { return lines(true); }
  std::string describe() const { return "exit " + std::to_string(status) + ", stderr:\n" + err + "stdout:\n" + out; }

 private:
  std::vector<std::string> lines(bool warnings) const {
    std::vector<std::string> result;
    std::istringstream in(err);
    for (std::string l; std::getline(in, l);)
      if ((l.rfind("brdfcl: warning:", 0) == 0) == warnings) result.push_back(l);
    return result;
  }
};

inline std::string slurp(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

// Writes `bytes` as the whole file `path`; throws when the write falls short, so that a test
// never runs on a half-written input.
inline void writeFile(const std::string& path, const std::string& bytes) {
  std::ofstream out(path, std::ios::binary);
  out << bytes;
  out.close();
  if (!out) throw std::runtime_error("cannot write test input " + path);
}

// The id of a process that has already exited and been reaped: one that no live process has.
inline pid_t deadPid() {
  const pid_t pid = ::fork();
  if (pid == 0) ::_exit(0);
  int status = 0;
  ::waitpid(pid, &status, 0);
  return pid;
}

// How to run the child beyond its arguments.
struct ProcessOptions {
  std::map<std::string, std::string> env;  // set (or replace) these variables
  std::size_t addressSpaceMiB = 0;         // RLIMIT_AS for the child; 0 leaves it alone
  std::string cwd;                         // working directory; empty keeps ours
  std::chrono::seconds timeout{120};
};

// argv[0] is the program's path. stdout/stderr go to files in `scratchDir`. Plain fork + execve:
// everything is prepared before the fork, so between the two the child only makes system calls,
// which is safe although this process runs PoCL's threads.
inline RunResult runProcess(std::vector<std::string> argv, const std::string& scratchDir, const ProcessOptions& o) {
  const std::string outPath = scratchDir + "/stdout", errPath = scratchDir + "/stderr";
  std::vector<std::string> envStrings;
  for (char** e = environ; *e; ++e) {
    const std::string kv = *e;
    if (!o.env.count(kv.substr(0, kv.find('=')))) envStrings.push_back(kv);
  }
  for (const auto& [k, v] : o.env) envStrings.push_back(k + "=" + v);
  std::vector<char*> args, envp;
  for (auto& a : argv) args.push_back(a.data());
  args.push_back(nullptr);
  for (auto& e : envStrings) envp.push_back(e.data());
  envp.push_back(nullptr);
  struct rlimit limit {};
  limit.rlim_cur = limit.rlim_max = rlim_t(o.addressSpaceMiB) << 20;

  const pid_t pid = ::fork();
  if (pid < 0) throw std::runtime_error(std::string("fork: ") + std::strerror(errno));
  if (pid == 0) {
    if (!o.cwd.empty() && ::chdir(o.cwd.c_str()) != 0) ::_exit(126);
    if (o.addressSpaceMiB > 0 && ::setrlimit(RLIMIT_AS, &limit) != 0) ::_exit(126);
    const int in = ::open("/dev/null", O_RDONLY);
    const int out = ::open(outPath.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
    const int err = ::open(errPath.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
    if (in < 0 || out < 0 || err < 0 || ::dup2(in, 0) < 0 || ::dup2(out, 1) < 0 || ::dup2(err, 2) < 0) ::_exit(126);
    ::execve(args[0], args.data(), envp.data());
    ::_exit(127);
  }

  // A hung child must fail the test, not the whole run.
  const auto deadline = std::chrono::steady_clock::now() + o.timeout;
  int status = 0;
  struct rusage usage {};
  for (;;) {
    const pid_t w = ::wait4(pid, &status, WNOHANG, &usage);
    if (w == pid) break;
    if (w < 0 && errno != EINTR) throw std::runtime_error(std::string("wait4: ") + std::strerror(errno));
    if (std::chrono::steady_clock::now() > deadline) {
      ::kill(pid, SIGKILL);
      ::waitpid(pid, &status, 0);
      throw std::runtime_error(argv[0] + " did not finish within " + std::to_string(o.timeout.count()) + " s");
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(2));
  }
  RunResult r;
  r.status = WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
  r.out = slurp(outPath);
  r.err = slurp(errPath);
  r.maxRssKiB = usage.ru_maxrss;
  return r;
}

inline RunResult runProcess(std::vector<std::string> argv, const std::string& scratchDir, const std::string& cwd = "",
                            std::chrono::seconds timeout = std::chrono::seconds(120)) {
  ProcessOptions o;
  o.cwd = cwd;
  o.timeout = timeout;
  return runProcess(std::move(argv), scratchDir, o);
}

}  // namespace brdfcl::test

namespace brdfcl::test {

// Where PoCL keeps its compiled kernels for this process: a child given its own XDG_CACHE_HOME
// keeps them by being given this as POCL_CACHE_DIR ("" when nothing locates it).
inline std::string poclCacheDir() {
  if (const char* p = std::getenv("POCL_CACHE_DIR"); p && *p) return p;
  if (const char* x = std::getenv("XDG_CACHE_HOME"); x && *x) return std::string(x) + "/pocl";
  if (const char* h = std::getenv("HOME"); h && *h) return std::string(h) + "/.cache/pocl";
  return "";
}

// A fresh directory under the system temp dir, removed with everything in it on destruction.
class ScratchDir {
 public:
  explicit ScratchDir(const std::string& tag) {
    static int counter = 0;
    path_ = std::filesystem::temp_directory_path() /
            ("brdfcl-" + tag + "-" + std::to_string(::getpid()) + "-" + std::to_string(counter++));
    std::filesystem::remove_all(path_);
    std::filesystem::create_directories(path_);
  }
  ~ScratchDir() {
    std::error_code ec;
    std::filesystem::remove_all(path_, ec);
  }
  ScratchDir(const ScratchDir&) = delete;
  ScratchDir& operator=(const ScratchDir&) = delete;

  std::string path(const std::string& name) const { return (path_ / name).string(); }
  std::string dir() const { return path_.string(); }
  // Names of the entries (files a run left behind, temporaries included).
  std::vector<std::string> list() const {
    std::vector<std::string> names;
    for (const auto& e : std::filesystem::directory_iterator(path_)) names.push_back(e.path().filename().string());
    std::sort(names.begin(), names.end());
    return names;
  }

 private:
  std::filesystem::path path_;
};

}  // namespace brdfcl::test
