// Reading a whole user file with POSIX calls, so that a failure can name its errno, within a
// byte cap; and writing a whole file.
#include "io/files.hpp"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstdint>
#include <cstring>

#include "brdfcl/error.hpp"
#include "io/input_limits.hpp"

namespace brdfcl::detail {

namespace {
// Reads into `out`; returns 0 or an errno. A regular file larger than maxRegular, or any other
// file that gives more than maxOther bytes, stops the read with EFBIG; `size` is then the regular
// file's size, or 0.
int readCapped(const std::string& path, std::string& out, std::size_t maxRegular, std::size_t maxOther,
               std::uint64_t& size) {
  size = 0;
  const int fd = ::open(path.c_str(), O_RDONLY | O_CLOEXEC);
  if (fd < 0) return errno;
  struct stat st {};
  if (::fstat(fd, &st) != 0 || S_ISDIR(st.st_mode)) {
    const int err = S_ISDIR(st.st_mode) ? EISDIR : errno;
    ::close(fd);
    return err;
  }
  const bool regular = S_ISREG(st.st_mode);
  if (regular && st.st_size > 0 && static_cast<std::uint64_t>(st.st_size) > maxRegular) {
    size = static_cast<std::uint64_t>(st.st_size);
    ::close(fd);
    return EFBIG;
  }
  // Checked as the bytes come: a regular file may grow while it is read, and pipes, devices and
  // /proc files report no size (or a wrong one) at all.
  const std::size_t cap = regular ? maxRegular : maxOther;
  out.clear();
  // st_size is only a hint: pipes and /proc files report 0, so keep reading until EOF.
  std::size_t capacity = regular && st.st_size > 0 ? static_cast<std::size_t>(st.st_size) + 1 : 65536;
  out.resize(std::min(capacity, cap == SIZE_MAX ? cap : cap + 1));
  std::size_t used = 0;
  for (;;) {
    if (used > cap) {
      ::close(fd);
      out.clear();
      out.shrink_to_fit();
      if (regular) size = used;
      return EFBIG;
    }
    if (used == out.size()) out.resize(std::min(out.size() * 2, cap == SIZE_MAX ? cap : cap + 1));
    const ssize_t n = ::read(fd, &out[used], out.size() - used);
    if (n < 0) {
      if (errno == EINTR) continue;
      const int err = errno;
      ::close(fd);
      return err;
    }
    if (n == 0) break;
    used += static_cast<std::size_t>(n);
  }
  ::close(fd);
  out.resize(used);
  return 0;
}
}  // namespace

int readWholeFile(const std::string& path, std::string& out) {
  std::uint64_t size = 0;
  return readCapped(path, out, SIZE_MAX, maxJsonBytes(), size);
}

std::size_t maxInputFileBytes(const std::string& path) {
  const bool glb = path.size() >= 4 && path.compare(path.size() - 4, 4, ".glb") == 0;
  return glb ? SIZE_MAX : maxJsonBytes();
}

void readInputFile(const std::string& path, const std::string& shown, const std::string& what, std::string& out,
                   std::size_t maxRegular) {
  const std::size_t cap = maxJsonBytes();
  std::uint64_t size = 0;
  const int err = readCapped(path, out, maxRegular == 0 ? cap : maxRegular, cap, size);
  if (err == EFBIG) throw Error(jsonBytesRefusal(shown, size, size ? (maxRegular == 0 ? cap : maxRegular) : cap));
  if (err) throw Error("cannot read " + what + "'" + shown + "': " + std::strerror(err));
}

// POSIX for the same reason: a stream's failure does not say whether the disk was full.
int writeWholeFile(const std::string& path, const void* data, std::size_t size) {
  const int fd = ::open(path.c_str(), O_WRONLY | O_TRUNC | O_CLOEXEC);
  if (fd < 0) return errno;
  const char* p = static_cast<const char*>(data);
  while (size > 0) {
    const ssize_t n = ::write(fd, p, size);
    if (n < 0 && errno == EINTR) continue;
    if (n < 0) {
      const int err = errno;
      ::close(fd);
      return err;
    }
    p += n;
    size -= static_cast<std::size_t>(n);
  }
  return ::close(fd) == 0 ? 0 : errno;
}

}  // namespace brdfcl::detail
