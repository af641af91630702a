// What the harnesses share: scratch files for the readers that take a path, and the one way a
// reader may refuse an input (a one-line brdfcl::Error, exit code 2); anything else aborts, so
// that libFuzzer keeps the input as a crash.
#pragma once
#include <fcntl.h>
#include <unistd.h>

#include <cerrno>
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>

#include "brdfcl/error.hpp"

namespace brdfcl::fuzz {

// $TMPDIR if set, else /dev/shm (memory: rewriting a file per input should not wear a disk).
inline std::string scratchDirectory() {
  if (const char* t = std::getenv("TMPDIR"); t && *t) return t;
  return ::access("/dev/shm", W_OK) == 0 ? "/dev/shm" : "/tmp";
}

[[noreturn]] inline void environmentFailure(const char* what, const std::string& path) {
  // Not a finding: the harness cannot run at all, and says so.
  std::fprintf(stderr, "fuzz harness: cannot %s '%s': %s\n", what, path.c_str(), std::strerror(errno));
  std::abort();
}

// One file per process, rewritten for every input: the readers choose the format by the
// extension, so the name must keep it. The pid keeps parallel fuzzing jobs apart.
class ScratchFile {
 public:
  explicit ScratchFile(const std::string& extension)
      : path_(scratchDirectory() + "/brdfcl-fuzz-" + std::to_string(::getpid()) + extension) {}
  ~ScratchFile() { ::unlink(path_.c_str()); }
  ScratchFile(const ScratchFile&) = delete;
  ScratchFile& operator=(const ScratchFile&) = delete;

  const std::string& write(const std::uint8_t* data, std::size_t size) const {
    const int fd = ::open(path_.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0600);
    if (fd < 0) environmentFailure("create", path_);
    for (std::size_t done = 0; done < size;) {
      const ssize_t n = ::write(fd, data + done, size - done);
      if (n < 0 && errno == EINTR) continue;
      if (n <= 0) environmentFailure("write", path_);
      done += static_cast<std::size_t>(n);
    }
    ::close(fd);
    return path_;
  }

 private:
  std::string path_;
};

// An empty directory for as long as the process runs, so that relative paths named by a fuzzed
// input resolve to nothing rather than to whatever lies in the current directory.
class EmptyDirectory {
 public:
  EmptyDirectory() {
    std::string t = scratchDirectory() + "/brdfcl-fuzz-dir-XXXXXX";
    if (!::mkdtemp(t.data())) environmentFailure("create", t);
    path_ = t;
  }
  ~EmptyDirectory() { ::rmdir(path_.c_str()); }
  EmptyDirectory(const EmptyDirectory&) = delete;
  EmptyDirectory& operator=(const EmptyDirectory&) = delete;
  const std::string& path() const { return path_; }

 private:
  std::string path_;
};

// The CLI prints what() as the whole message of a failed run: it must be one non-empty line,
// with the exit status of errors the user can fix.
template <class Read>
void expectCleanRefusal(Read&& read) {
  try {
    read();
  } catch (const Error& e) {
    const std::string m = e.what();
    if (m.empty() || m.find_first_of("\r\n") != std::string::npos || e.exitCode() != 2) {
      std::fprintf(stderr, "fuzz harness: malformed brdfcl::Error (exit code %d): [%s]\n", e.exitCode(), m.c_str());
      std::abort();
    }
  }
}

}  // namespace brdfcl::fuzz
