// The temporaries registry and the SIGINT/SIGTERM/SIGHUP handler that empties it, and the sweep
// that removes temporaries of dead processes. The handler only reads fixed arrays and atomics and
// calls unlink and _exit, so it is async-signal-safe whichever thread it interrupts.
#include "io/temporaries.hpp"

#include <dirent.h>
#include <fcntl.h>
#include <signal.h>
#include <sys/stat.h>
#include <unistd.h>

#include <atomic>
#include <cerrno>
#include <cstring>
#include <filesystem>

#include "brdfcl/cleanup.hpp"

namespace brdfcl::detail {
namespace {

// A slot is free (0), being filled or emptied (1), or holds a live temporary (2). The handler
// unlinks only state-2 paths, which are complete strings.
constexpr int kSlots = 256;
constexpr std::size_t kPathMax = 4096;
struct Slot {
  std::atomic<int> state{0};
  char path[kPathMax];
};
Slot slots[kSlots];
static_assert(std::atomic<int>::is_always_lock_free, "the signal handler reads the slot states");

std::string absolute(const std::string& path) {
  std::error_code ec;
  const auto p = std::filesystem::absolute(path, ec);
  return ec ? path : p.string();
}

void removeTemporariesAndExit(int signo) {
  for (Slot& s : slots)
    if (s.state.load(std::memory_order_acquire) == 2) ::unlink(s.path);
  ::_exit(128 + signo);
}

bool allDigits(const std::string& s) {
  if (s.empty() || s.size() > 18) return false;
  for (char c : s)
    if (c < '0' || c > '9') return false;
  return true;
}

}  // namespace

bool registerTemporary(const std::string& path) {
  const std::string abs = absolute(path);
  if (abs.size() >= kPathMax) return false;
  for (Slot& s : slots) {
    int expected = 0;
    if (!s.state.compare_exchange_strong(expected, 1, std::memory_order_acquire)) continue;
    std::memcpy(s.path, abs.c_str(), abs.size() + 1);
    s.state.store(2, std::memory_order_release);
    return true;
  }
  return false;
}

void deregisterTemporary(const std::string& path) {
  const std::string abs = absolute(path);
  for (Slot& s : slots) {
    int expected = 2;
    if (s.state.load(std::memory_order_acquire) != 2 || std::strcmp(s.path, abs.c_str()) != 0) continue;
    if (s.state.compare_exchange_strong(expected, 1, std::memory_order_acquire)) {
      s.path[0] = '\0';
      s.state.store(0, std::memory_order_release);
      return;
    }
  }
}

bool parseTemporaryName(const std::string& name, long& pid) {
  // ".<name>.tmp.<pid>.<n>": read from the end, since <name> may itself contain ".tmp.".
  const auto lastDot = name.rfind('.');
  if (lastDot == std::string::npos || lastDot == 0 || !allDigits(name.substr(lastDot + 1))) return false;
  const auto pidDot = name.rfind('.', lastDot - 1);
  if (pidDot == std::string::npos || !allDigits(name.substr(pidDot + 1, lastDot - pidDot - 1))) return false;
  const std::string head = name.substr(0, pidDot);
  if (name[0] != '.' || head.size() < 6 || head.compare(head.size() - 4, 4, ".tmp") != 0) return false;
  pid = std::stol(name.substr(pidDot + 1, lastDot - pidDot - 1));
  return pid > 0;
}

void removeStaleTemporaries(const std::string& dir) {
  DIR* d = ::opendir(dir.empty() ? "." : dir.c_str());
  if (!d) return;
  const long self = static_cast<long>(::getpid());
  while (const dirent* e = ::readdir(d)) {
    long pid = 0;
    if (!parseTemporaryName(e->d_name, pid) || pid == self) continue;
    // EPERM means the process exists under another user: only ESRCH proves it is gone.
    if (::kill(static_cast<pid_t>(pid), 0) == 0 || errno != ESRCH) continue;
    struct stat st {};
    if (::fstatat(::dirfd(d), e->d_name, &st, AT_SYMLINK_NOFOLLOW) == 0 && S_ISREG(st.st_mode))
      ::unlinkat(::dirfd(d), e->d_name, 0);
  }
  ::closedir(d);
}

}  // namespace brdfcl::detail

namespace brdfcl {

void installSignalCleanup() {
  for (const int signo : {SIGINT, SIGTERM, SIGHUP}) {
    struct sigaction old {};
    if (::sigaction(signo, nullptr, &old) == 0 && old.sa_handler == SIG_IGN) continue;
    struct sigaction sa {};
    sa.sa_handler = detail::removeTemporariesAndExit;
    sigemptyset(&sa.sa_mask);
    sigaddset(&sa.sa_mask, SIGINT);
    sigaddset(&sa.sa_mask, SIGTERM);
    sigaddset(&sa.sa_mask, SIGHUP);
    ::sigaction(signo, &sa, nullptr);
  }
}

}  // namespace brdfcl
