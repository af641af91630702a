// The samples file's bytes: a regular file (or stdin redirected from one) read with pread into
// the caller's buffer, never mapped; a pipe read whole, up to the JSON input limit.
#include "io/sample_source.hpp"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstring>

#include "brdfcl/error.hpp"
#include "io/input_limits.hpp"

namespace brdfcl::detail::samples {

std::string displayName(const std::string& path) { return path == "-" ? "<stdin>" : printable(path, 300); }

Source::Source(const std::string& path) : name_(displayName(path)) {
  // stdin redirected from a regular file streams like that file; a pipe is read whole below.
  if (path == "-") {
    fd_ = STDIN_FILENO;
    ownsFd_ = false;
  } else {
    fd_ = ::open(path.c_str(), O_RDONLY | O_CLOEXEC);
  }
  if (fd_ < 0) fail(errno);
  // The destructor does not run when the constructor throws: close before failing.
  const auto failOpen = [this](int err) {
    release();
    fail(err);
  };
  struct stat st {};
  if (::fstat(fd_, &st) != 0 || S_ISDIR(st.st_mode)) failOpen(S_ISDIR(st.st_mode) ? EISDIR : errno);
  if (S_ISREG(st.st_mode) && st.st_size > 0) {
    size_ = static_cast<std::size_t>(st.st_size);
    return;
  }
  const std::size_t cap = detail::maxJsonBytes();
  std::size_t used = 0;
  whole_.resize(std::min<std::size_t>(65536, cap + 1));
  for (;;) {
    if (used > cap) {
      release();
      throw Error(detail::jsonBytesRefusal(name_, 0, cap));
    }
    if (used == whole_.size()) whole_.resize(std::min(whole_.size() * 2, cap + 1));
    const ssize_t n = ::read(fd_, &whole_[used], whole_.size() - used);
    if (n < 0 && errno == EINTR) continue;
    if (n < 0) failOpen(errno);
    if (n == 0) break;
    used += static_cast<std::size_t>(n);
  }
  whole_.resize(used);
  size_ = used;
  release();
}

std::size_t Source::readAt(std::size_t offset, char* dst, std::size_t n) const {
  if (fd_ < 0) {
    if (offset >= whole_.size()) return 0;
    n = std::min(n, whole_.size() - offset);
    std::memcpy(dst, whole_.data() + offset, n);
    return n;
  }
  std::size_t done = 0;
  while (done < n) {
    const ssize_t r = ::pread(fd_, dst + done, n - done, static_cast<off_t>(offset + done));
    if (r < 0 && errno == EINTR) continue;
    if (r < 0) fail(errno);
    if (r == 0) break;
    done += static_cast<std::size_t>(r);
  }
  return done;
}

[[noreturn]] void Source::fail(int err) const {
  throw Error("cannot read samples file '" + name_ + "': " + std::strerror(err));
}

void Source::release() {
  if (fd_ >= 0 && ownsFd_) ::close(fd_);
  fd_ = -1;
}

}  // namespace brdfcl::detail::samples
