// openInside/readInside (confined_open.hpp): a walk from the folder's descriptor, one component
// at a time with O_NOFOLLOW, so that neither "..", an absolute name nor a link inside the folder
// reaches a file outside it; lstat-style checks before each open keep devices and FIFOs unopened.
#include "io/confined_open.hpp"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cctype>
#include <cerrno>
#include <vector>

namespace brdfcl::detail {
namespace {

// Closes on every path out of the walk.
class Fd {
 public:
  explicit Fd(int fd = -1) : fd_(fd) {}
  Fd(const Fd&) = delete;
  Fd& operator=(const Fd&) = delete;
  ~Fd() { reset(); }
  void reset(int fd = -1) {
    if (fd_ >= 0) ::close(fd_);
    fd_ = fd;
  }
  int get() const { return fd_; }
  int release() {
    const int fd = fd_;
    fd_ = -1;
    return fd;
  }

 private:
  int fd_;
};

// "a/./b/../c" as {"a", "c"}; false when ".." climbs above the start.
bool components(const std::string& name, std::vector<std::string>& out) {
  std::size_t start = 0;
  while (start <= name.size()) {
    std::size_t end = name.find('/', start);
    if (end == std::string::npos) end = name.size();
    const std::string c = name.substr(start, end - start);
    if (c == "..") {
      if (out.empty()) return false;
      out.pop_back();
    } else if (!c.empty() && c != ".") {
      out.push_back(c);
    }
    start = end + 1;
  }
  return true;
}

int fail(Opened& result, Opened::Outcome outcome, int error = 0) {
  result.outcome = outcome;
  result.error = error;
  return -1;
}

// The reason an openat of `name` under `dir` failed: a link there, else errno `e`.
int failedOpen(Opened& result, int dir, const std::string& name, int e) {
  struct stat st {};
  if ((e == ELOOP || e == ENOTDIR || e == EMLINK) && ::fstatat(dir, name.c_str(), &st, AT_SYMLINK_NOFOLLOW) == 0 &&
      S_ISLNK(st.st_mode))
    return fail(result, Opened::Outcome::Link);
  return fail(result, Opened::Outcome::Unreadable, e);
}

// The regular-file and size checks on an open descriptor.
int checked(Fd& fd, const OpenRules& rules, Opened& result) {
  struct stat st {};
  if (::fstat(fd.get(), &st) != 0) return fail(result, Opened::Outcome::Unreadable, errno);
  if (!S_ISREG(st.st_mode)) return fail(result, Opened::Outcome::NotRegular);
  result.size = std::uint64_t(st.st_size);
  if (result.size < rules.atLeast) return fail(result, Opened::Outcome::TooSmall);
  if (result.size > rules.sizeAtMost) return fail(result, Opened::Outcome::TooLarge);
  // O_NONBLOCK kept a FIFO from blocking the open; a regular file reads the same without it.
  const int flags = ::fcntl(fd.get(), F_GETFL);
  if (flags >= 0) ::fcntl(fd.get(), F_SETFL, flags & ~O_NONBLOCK);
  result.outcome = Opened::Outcome::Ok;
  return fd.release();
}

constexpr int kFileFlags = O_RDONLY | O_CLOEXEC | O_NOCTTY | O_NONBLOCK;

}  // namespace

std::string uriScheme(const std::string& uri) {
  // RFC 3986: ALPHA *( ALPHA / DIGIT / "+" / "-" / "." ) ":"
  if (uri.empty() || !std::isalpha(static_cast<unsigned char>(uri[0]))) return "";
  for (std::size_t i = 1; i < uri.size(); ++i) {
    const unsigned char c = static_cast<unsigned char>(uri[i]);
    if (c == ':') return uri.substr(0, i);
    if (!std::isalnum(c) && c != '+' && c != '-' && c != '.') return "";
  }
  return "";
}

std::string uriDecoded(const std::string& uri) {
  auto hex = [](char c) -> int {
    if (c >= '0' && c <= '9') return c - '0';
    if (c >= 'a' && c <= 'f') return c - 'a' + 10;
    if (c >= 'A' && c <= 'F') return c - 'A' + 10;
    return 0;
  };
  std::string out;
  for (std::size_t i = 0; i < uri.size(); ++i) {
    if (uri[i] == '+') {
      out += ' ';
    } else if (uri[i] == '%' && uri.size() > i + 2) {
      out += char((hex(uri[i + 1]) << 4) | hex(uri[i + 2]));
      i += 2;
    } else {
      out += uri[i];
    }
  }
  return out;
}

bool staysInside(const std::string& name) {
  std::vector<std::string> parts;
  return !name.empty() && name[0] != '/' && components(name, parts);
}

int openInside(const std::string& dir, const std::string& name, const OpenRules& rules, Opened& result) {
  result = Opened{};
  if (name.find('\0') != std::string::npos) return fail(result, Opened::Outcome::Unreadable, EINVAL);
  if (rules.allowOutside) {
    std::string path;
    if (name.empty()) path = dir.empty() ? "." : dir;
    else if (name[0] == '/' || dir.empty()) path = name;
    else path = dir + (dir.back() == '/' ? "" : "/") + name;
    struct stat st {};
    if (::stat(path.c_str(), &st) != 0) return fail(result, Opened::Outcome::Unreadable, errno);
    if (!S_ISREG(st.st_mode)) return fail(result, Opened::Outcome::NotRegular);
    Fd fd(::open(path.c_str(), kFileFlags));
    if (fd.get() < 0) return fail(result, Opened::Outcome::Unreadable, errno);
    return checked(fd, rules, result);
  }
  std::vector<std::string> parts;
  if (!name.empty() && name[0] == '/') return fail(result, Opened::Outcome::Outside);
  if (!components(name, parts)) return fail(result, Opened::Outcome::Outside);
  if (parts.empty()) return fail(result, Opened::Outcome::NotRegular);  // the folder itself
  // The folder is where the naming file lies; reaching it through a link is the user's choice.
  Fd at(::open(dir.empty() ? "." : dir.c_str(), O_PATH | O_DIRECTORY | O_CLOEXEC));
  if (at.get() < 0) return fail(result, Opened::Outcome::Unreadable, errno);
  for (std::size_t i = 0; i < parts.size(); ++i) {
    const std::string& part = parts[i];
    const bool last = i + 1 == parts.size();
    struct stat st {};
    if (::fstatat(at.get(), part.c_str(), &st, AT_SYMLINK_NOFOLLOW) != 0)
      return fail(result, Opened::Outcome::Unreadable, errno);
    if (S_ISLNK(st.st_mode)) return fail(result, Opened::Outcome::Link);
    if (!last) {
      if (!S_ISDIR(st.st_mode)) return fail(result, Opened::Outcome::Unreadable, ENOTDIR);
      const int next = ::openat(at.get(), part.c_str(), O_PATH | O_DIRECTORY | O_NOFOLLOW | O_CLOEXEC);
      if (next < 0) return failedOpen(result, at.get(), part, errno);
      at.reset(next);
      continue;
    }
    if (!S_ISREG(st.st_mode)) return fail(result, Opened::Outcome::NotRegular);
    Fd fd(::openat(at.get(), part.c_str(), kFileFlags | O_NOFOLLOW));
    if (fd.get() < 0) return failedOpen(result, at.get(), part, errno);
    return checked(fd, rules, result);
  }
  return fail(result, Opened::Outcome::NotRegular);
}

Opened readInside(const std::string& dir, const std::string& name, const OpenRules& rules, std::string& out) {
  Opened result;
  out.clear();
  Fd fd(openInside(dir, name, rules, result));
  if (fd.get() < 0) return result;
  const std::uint64_t want = result.size < rules.readAtMost ? result.size : rules.readAtMost;
  out.resize(std::size_t(want));
  std::size_t used = 0;
  while (used < out.size()) {
    const ssize_t n = ::read(fd.get(), &out[used], out.size() - used);
    if (n < 0 && errno == EINTR) continue;
    if (n < 0) {
      const int e = errno;
      out.clear();
      result.outcome = Opened::Outcome::Unreadable;
      result.error = e;
      return result;
    }
    if (n == 0) break;  // shrank since fstat
    used += std::size_t(n);
  }
  out.resize(used);
  if (used < rules.atLeast) {
    result.outcome = Opened::Outcome::TooSmall;
    result.size = used;
    out.clear();
  }
  return result;
}

}  // namespace brdfcl::detail
