// The temporaries registry and the SIGINT/SIGTERM/SIGHUP/SIGPIPE handler that empties it, the
// temporaries' names, and the sweep that removes old temporaries of dead processes of this host. The handler only reads fixed arrays and atomics and
// calls unlink and _exit, so it is async-signal-safe whichever thread it interrupts.
#include "io/temporaries.hpp"

#include <dirent.h>
#include <fcntl.h>
#include <signal.h>
#include <sys/random.h>
#include <sys/stat.h>
#include <unistd.h>

#include <atomic>
#include <cerrno>
#include <chrono>
#include <cstring>
#include <ctime>
#include <filesystem>
#include <vector>

#include "io/cleanup.hpp"

namespace brdfcl::detail {
namespace {

// A slot is free (0), being filled or emptied (1), or holds a live temporary (2). The handler
// unlinks only state-2 paths, which are complete strings.
constexpr int kSlots = 256;
constexpr std::size_t kPathMax = 4096;
// Every member initialized, so the array is constant-initialized (zero pages of .bss) rather than
// written slot by slot before main: 256 page faults off every process start.
struct Slot {
  std::atomic<int> state{0};
  char path[kPathMax] = {};
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

constexpr char kPrefix[] = ".brdfcl.tmp.";
constexpr std::size_t kHostMax = 160;  // keeps the whole name within NAME_MAX
constexpr char kHex[] = "0123456789abcdef";

bool isHostByte(unsigned char c) {
  return (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') || c == '-';
}

}  // namespace

std::string encodeHostName(const std::string& host) {
  std::string out;
  for (const unsigned char c : host) {
    if (isHostByte(c)) {
      out += char(c);
    } else {
      out += '_';
      out += kHex[c >> 4];
      out += kHex[c & 15];
    }
  }
  if (out.size() <= kHostMax) return out;
  std::uint64_t h = 1469598103934665603ull;  // FNV-1a
  for (const unsigned char c : out) h = (h ^ c) * 1099511628211ull;
  std::string tail = "~";
  for (int i = 15; i >= 0; --i) tail += kHex[(h >> (4 * i)) & 15];
  // Cut between escapes, never inside one.
  std::size_t cut = 0;
  for (std::size_t i = 0; i < out.size();) {
    const std::size_t step = out[i] == '_' ? 3 : 1;
    if (i + step > kHostMax - tail.size()) break;
    i += step;
    cut = i;
  }
  return out.substr(0, cut) + tail;
}

namespace {

bool isLowerHex(char c) { return (c >= '0' && c <= '9') || (c >= 'a' && c <= 'f'); }

bool isEncodedHost(const std::string& s) {
  if (s.empty() || s.size() > kHostMax) return false;
  for (std::size_t i = 0; i < s.size(); ++i) {
    const unsigned char c = static_cast<unsigned char>(s[i]);
    if (isHostByte(c) || c == '~') continue;
    if (c != '_' || i + 2 >= s.size() || !isLowerHex(s[i + 1]) || !isLowerHex(s[i + 2])) return false;
    i += 2;
  }
  return true;
}

// Decimal without sign or leading zeros ("0" itself only where `zero` allows it).
bool parseNumber(const std::string& s, std::size_t maxDigits, bool zero, std::uint64_t& value) {
  if (s.empty() || s.size() > maxDigits || (s[0] == '0' && (s.size() > 1 || !zero))) return false;
  value = 0;
  for (const char c : s) {
    if (c < '0' || c > '9') return false;
    const std::uint64_t next = value * 10 + std::uint64_t(c - '0');
    if (next / 10 != value) return false;
    value = next;
  }
  return true;
}

std::uint64_t randomBits() {
  std::uint64_t r = 0;
  if (::getrandom(&r, sizeof r, GRND_NONBLOCK) == static_cast<ssize_t>(sizeof r)) return r;
  // No entropy yet (early boot): the time, the pid and a counter, mixed (splitmix64).
  static std::atomic<std::uint64_t> counter{0};
  std::uint64_t z = static_cast<std::uint64_t>(std::chrono::steady_clock::now().time_since_epoch().count()) ^
                    (static_cast<std::uint64_t>(::getpid()) << 32) ^ (counter.fetch_add(1) * 0x9e3779b97f4a7c15ull);
  z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ull;
  z = (z ^ (z >> 27)) * 0x94d049bb133111ebull;
  return z ^ (z >> 31);
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

TemporaryOwner thisProcess() {
  TemporaryOwner me;
  char host[256] = {};
  me.host = encodeHostName(::gethostname(host, sizeof host - 1) == 0 && host[0] != '\0' ? host : "unknown-host");
  // "pid:[4026531836]": the namespace's inode tells containers that share a host name apart.
  char link[64] = {};
  const ssize_t n = ::readlink("/proc/self/ns/pid", link, sizeof link - 1);
  if (n > 0) {
    const std::string s(link, static_cast<std::size_t>(n));
    const auto open = s.find('['), close = s.find(']');
    std::uint64_t inode = 0;
    if (open != std::string::npos && close != std::string::npos && close > open &&
        parseNumber(s.substr(open + 1, close - open - 1), 20, true, inode))
      me.pidNamespace = inode;
  }
  me.pid = static_cast<long>(::getpid());
  return me;
}

std::string temporaryName(const TemporaryOwner& owner) {
  const std::uint64_t r = randomBits();
  std::string random;
  for (int i = 15; i >= 0; --i) random += kHex[(r >> (4 * i)) & 15];
  return kPrefix + owner.host + "." + std::to_string(owner.pidNamespace) + "." + std::to_string(owner.pid) + "." +
         random;
}

bool parseTemporaryName(const std::string& name, TemporaryOwner& owner) {
  const std::size_t prefix = sizeof kPrefix - 1;
  if (name.size() > 255 || name.compare(0, prefix, kPrefix) != 0) return false;
  std::vector<std::string> fields;
  std::size_t at = prefix;
  for (;;) {
    const auto dot = name.find('.', at);
    fields.push_back(name.substr(at, dot == std::string::npos ? std::string::npos : dot - at));
    if (dot == std::string::npos) break;
    at = dot + 1;
  }
  if (fields.size() != 4 || !isEncodedHost(fields[0]) || fields[3].size() != 16) return false;
  for (const char c : fields[3])
    if (!isLowerHex(c)) return false;
  std::uint64_t ns = 0, pid = 0;
  if (!parseNumber(fields[1], 20, true, ns) || !parseNumber(fields[2], 10, false, pid) || pid > 0x7fffffffu)
    return false;
  owner.host = fields[0];
  owner.pidNamespace = ns;
  owner.pid = static_cast<long>(pid);
  return true;
}

bool isStaleTemporary(int dirFd, const char* name, const TemporaryOwner& self) {
  TemporaryOwner owner;
  if (!parseTemporaryName(name, owner) || owner.host != self.host || owner.pidNamespace != self.pidNamespace ||
      owner.pid == self.pid)
    return false;
  // EPERM means the process exists under another user: only ESRCH proves it is gone.
  if (::kill(static_cast<pid_t>(owner.pid), 0) == 0 || errno != ESRCH) return false;
  struct stat st {};
  if (::fstatat(dirFd, name, &st, AT_SYMLINK_NOFOLLOW) != 0 || !S_ISREG(st.st_mode)) return false;
  return std::time(nullptr) - st.st_mtime >= kStaleTemporarySeconds;
}

void removeStaleTemporaries(const std::string& dir) {
  DIR* d = ::opendir(dir.empty() ? "." : dir.c_str());
  if (!d) return;
  const TemporaryOwner me = thisProcess();
  while (const dirent* e = ::readdir(d))
    if (isStaleTemporary(::dirfd(d), e->d_name, me)) ::unlinkat(::dirfd(d), e->d_name, 0);
  ::closedir(d);
}

}  // namespace brdfcl::detail

namespace brdfcl {

void installSignalCleanup() {
  // SIGPIPE: a reader that goes away (`brdfcl ... --out - | head`) ends the run as it ends any
  // program, but not before the spool of the output is removed.
  for (const int signo : {SIGINT, SIGTERM, SIGHUP, SIGPIPE}) {
    struct sigaction old {};
    if (::sigaction(signo, nullptr, &old) == 0 && old.sa_handler == SIG_IGN) continue;
    struct sigaction sa {};
    sa.sa_handler = detail::removeTemporariesAndExit;
    sigemptyset(&sa.sa_mask);
    sigaddset(&sa.sa_mask, SIGINT);
    sigaddset(&sa.sa_mask, SIGTERM);
    sigaddset(&sa.sa_mask, SIGHUP);
    sigaddset(&sa.sa_mask, SIGPIPE);
    ::sigaction(signo, &sa, nullptr);
  }
}

}  // namespace brdfcl
