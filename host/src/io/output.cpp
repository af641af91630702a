// The output-file layer every writer of brdfcl goes through: "-" is stdout, symlinks are followed
// to the file they name, FIFOs and devices are written in place, regular files atomically
// (a registered temporary beside the target, renamed into place), directories are refused.
#include "io/output.hpp"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <cctype>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <vector>

#include "brdfcl/error.hpp"
#include "brdfcl/io.hpp"
#include "io/files.hpp"
#include "io/messages.hpp"
#include "io/temporaries.hpp"

namespace brdfcl::detail {
namespace {

namespace fs = std::filesystem;

std::atomic<unsigned> tmpCounter{0};

std::string defaultHead(const std::string& userPath) { return "cannot write '" + printable(userPath, 300) + "': "; }

[[noreturn]] void failErrno(const std::string& userPath, int err) {
  throw Error(defaultHead(userPath) + std::strerror(err));
}

bool isFileName(const std::string& path) {
  const std::string name = fs::path(path).filename().string();
  return !name.empty() && name != "." && name != "..";
}

}  // namespace

namespace {
// /dev/stdout too: reopening it through /proc would lose the shell's O_APPEND (">>").
bool isStdout(const std::string& userPath) { return userPath == "-" || userPath == "/dev/stdout"; }

// Replacing a FIFO or a device by a file would hide the output from whoever reads it.
bool isExistingNonRegular(const struct stat& st) { return !S_ISREG(st.st_mode) && !S_ISDIR(st.st_mode); }
}  // namespace

bool isStreamTarget(const std::string& userPath) {
  struct stat st {};
  return isStdout(userPath) || (::stat(userPath.c_str(), &st) == 0 && isExistingNonRegular(st));
}

OutputTarget resolveOutputWithHead(const std::string& userPath, const std::string& head) {
  if (isStdout(userPath)) return {OutputKind::Stdout, userPath};
  if (!isFileName(userPath)) throw Error(head + "not a file name");
  struct stat st {};
  if (::stat(userPath.c_str(), &st) == 0) {
    if (S_ISDIR(st.st_mode)) throw Error(head + "it is a directory; name a file inside it");
    if (isExistingNonRegular(st)) return {OutputKind::Stream, userPath};
  }
  // A regular file or nothing yet: the atomic rename must happen at the end of the link chain,
  // in the target's directory, or the link itself would be replaced by a plain file.
  std::string p = userPath;
  for (int hops = 0;; ++hops) {
    struct stat l {};
    if (::lstat(p.c_str(), &l) != 0 || !S_ISLNK(l.st_mode)) break;
    if (hops == 40) throw Error(head + std::strerror(ELOOP));
    // /proc's links (/dev/stdout -> /proc/self/fd/1) name open files, not paths to rename over:
    // write through them in place, as a shell redirection would.
    if (p.rfind("/proc/", 0) == 0) return {OutputKind::Stream, userPath};
    std::vector<char> buf(4096);
    const ssize_t n = ::readlink(p.c_str(), buf.data(), buf.size());
    if (n < 0 || static_cast<std::size_t>(n) >= buf.size()) throw Error(head + std::strerror(n < 0 ? errno : ENAMETOOLONG));
    const std::string link(buf.data(), static_cast<std::size_t>(n));
    p = !link.empty() && link[0] == '/' ? link : (fs::path(p).parent_path() / link).string();
  }
  if (!isFileName(p)) throw Error(head + "not a file name");
  return {OutputKind::File, p};
}

OutputTarget resolveOutput(const std::string& userPath) { return resolveOutputWithHead(userPath, defaultHead(userPath)); }

std::string outputExtension(const std::string& userPath, const OutputTarget& target) {
  if (target.kind == OutputKind::Stdout) return ".csv";
  const std::string name = fs::path(userPath).filename().string();
  const auto dot = name.find_last_of('.');
  if (dot == std::string::npos || dot == 0) return target.kind == OutputKind::Stream ? ".csv" : "";
  std::string ext = name.substr(dot);
  std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return char(std::tolower(c)); });
  return ext;
}

std::string createTemporary(const std::string& finalPath, const std::string& userPath) {
  const fs::path target(finalPath);
  const std::string fileName = target.filename().string();
  removeStaleTemporaries(target.parent_path().string());
  const std::string stem = "." + fileName.substr(0, 200) + ".tmp." + std::to_string(::getpid()) + ".";
  for (int attempt = 0;; ++attempt) {
    const std::string tmp = (target.parent_path() / (stem + std::to_string(tmpCounter.fetch_add(1)))).string();
    // Registered before it exists, so that no signal can come between creation and registration.
    const bool registered = registerTemporary(tmp);
    // O_EXCL: a stale temporary of a crashed run with the same pid must not be reused.
    const int fd = ::open(tmp.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, 0666);
    if (fd >= 0) {
      ::close(fd);
      return tmp;
    }
    const int err = errno;
    if (registered) deregisterTemporary(tmp);
    if (err != EEXIST || attempt > 100) failErrno(userPath, err);
  }
}

std::string createSpool(const std::string& userPath) {
  std::error_code ec;
  fs::path dir = fs::temp_directory_path(ec);
  if (ec) dir = "/tmp";
  return createTemporary((dir / "brdfcl-spool").string(), userPath);
}

void commitTemporary(const std::string& tmp, const std::string& finalPath, const std::string& userPath) {
  if (std::rename(tmp.c_str(), finalPath.c_str()) != 0) failErrno(userPath, errno);
  deregisterTemporary(tmp);
}

void removeTemporary(const std::string& tmp) {
  ::unlink(tmp.c_str());
  deregisterTemporary(tmp);
}

int openStream(const OutputTarget& target, const std::string& userPath) {
  if (target.kind == OutputKind::Stdout) return STDOUT_FILENO;
  // No O_TRUNC: FIFOs and devices have nothing to truncate, and a /proc link to a regular file
  // (/dev/stdout redirected to a file) keeps the shell's offset semantics only without it.
  const int fd = ::open(target.path.c_str(), O_WRONLY | O_CLOEXEC | O_NOCTTY);
  if (fd < 0) failErrno(userPath, errno);
  return fd;
}

void closeStream(int fd, const OutputTarget& target, const std::string& userPath) {
  if (target.kind == OutputKind::Stdout) return;
  if (::close(fd) != 0) failErrno(userPath, errno);
}

void writeAll(int fd, const void* data, std::size_t size, const std::string& userPath) {
  const char* p = static_cast<const char*>(data);
  while (size > 0) {
    const ssize_t n = ::write(fd, p, size);
    if (n < 0) {
      if (errno == EINTR) continue;
      failErrno(userPath, errno);
    }
    p += n;
    size -= static_cast<std::size_t>(n);
  }
}

void copyFile(const std::string& from, int fd, const std::string& userPath) {
  const int in = ::open(from.c_str(), O_RDONLY | O_CLOEXEC);
  if (in < 0) failErrno(userPath, errno);
  std::vector<char> buf(1 << 20);
  for (;;) {
    const ssize_t n = ::read(in, buf.data(), buf.size());
    if (n < 0 && errno == EINTR) continue;
    if (n < 0) {
      const int err = errno;
      ::close(in);
      failErrno(userPath, err);
    }
    if (n == 0) break;
    try {
      writeAll(fd, buf.data(), static_cast<std::size_t>(n), userPath);
    } catch (...) {
      ::close(in);
      throw;
    }
  }
  ::close(in);
}

std::string npyHeader(const std::string& shape) {
  constexpr std::size_t kTotal = 128;
  std::string dict = "{'descr': '<f4', 'fortran_order': False, 'shape': " + shape + ", }";
  dict.append(kTotal - 10 - dict.size() - 1, ' ');
  dict += '\n';
  const std::size_t len = dict.size();
  const char prefix[10] = {
      '\x93', 'N', 'U', 'M', 'P', 'Y', 1, 0, static_cast<char>(len & 0xff), static_cast<char>(len >> 8)};
  return std::string(prefix, sizeof prefix) + dict;
}

}  // namespace brdfcl::detail

namespace brdfcl {

using detail::OutputKind;

void writeAtomically(const std::string& path, const std::function<void(const std::string& tmpPath)>& write) {
  const detail::OutputTarget t = detail::resolveOutput(path);
  if (t.kind == OutputKind::File) {
    const std::string tmp = detail::createTemporary(t.path, path);
    try {
      write(tmp);
      detail::commitTemporary(tmp, t.path, path);
    } catch (...) {
      detail::removeTemporary(tmp);
      throw;
    }
    return;
  }
  // Writers that need a seekable file (OpenEXR) write a spool, which is then streamed.
  const std::string spool = detail::createSpool(path);
  try {
    write(spool);
    const int fd = detail::openStream(t, path);
    try {
      detail::copyFile(spool, fd, path);
    } catch (...) {
      if (t.kind == OutputKind::Stream) ::close(fd);
      throw;
    }
    detail::closeStream(fd, t, path);
  } catch (...) {
    detail::removeTemporary(spool);
    throw;
  }
  detail::removeTemporary(spool);
}

void writeOutput(const std::string& path, const void* data, std::size_t size) {
  const detail::OutputTarget t = detail::resolveOutput(path);
  if (t.kind == OutputKind::File) {
    const std::string tmp = detail::createTemporary(t.path, path);
    try {
      if (const int err = detail::writeWholeFile(tmp, data, size))
        throw Error("cannot write '" + detail::printable(path, 300) + "': " + std::strerror(err));
      detail::commitTemporary(tmp, t.path, path);
    } catch (...) {
      detail::removeTemporary(tmp);
      throw;
    }
    return;
  }
  const int fd = detail::openStream(t, path);
  try {
    detail::writeAll(fd, data, size, path);
  } catch (...) {
    if (t.kind == OutputKind::Stream) ::close(fd);
    throw;
  }
  detail::closeStream(fd, t, path);
}

void checkOutputPath(const std::string& option, const std::string& path) {
  const std::string head = option + " '" + detail::printable(path, 300) + "': cannot write: ";
  const detail::OutputTarget t = detail::resolveOutputWithHead(path, head);
  if (t.kind == OutputKind::Stdout) return;
  if (t.kind == OutputKind::Stream) {
    if (::access(path.c_str(), W_OK) != 0) throw Error(head + std::strerror(errno));
    return;
  }
  struct stat st {};
  if (::stat(t.path.c_str(), &st) == 0 && ::access(t.path.c_str(), W_OK) != 0) throw Error(head + std::strerror(errno));
  const std::filesystem::path dir = std::filesystem::path(t.path).parent_path();
  const std::string d = dir.empty() ? "." : dir.string();
  if (::stat(d.c_str(), &st) != 0) throw Error(head + std::strerror(errno));
  if (!S_ISDIR(st.st_mode)) throw Error(head + "'" + detail::printable(d, 300) + "' is not a directory");
  if (::access(d.c_str(), W_OK | X_OK) != 0) throw Error(head + std::strerror(errno));
}

void checkOutputPath(const std::string& option, const std::string& path, const std::vector<std::string>& extensions) {
  checkOutputPath(option, path);
  const detail::OutputTarget t = detail::resolveOutput(path);
  if (t.kind == OutputKind::Stdout) return;
  const std::string ext = detail::outputExtension(path, t);
  const std::string name = std::filesystem::path(path).filename().string();
  if (t.kind == OutputKind::Stream && name.find('.', 1) == std::string::npos) return;  // /dev/null, a FIFO
  if (std::find(extensions.begin(), extensions.end(), ext) != extensions.end()) return;
  std::string list;
  for (std::size_t i = 0; i < extensions.size(); ++i) list += (i ? ", " : "") + extensions[i];
  throw Error(option + " '" + detail::printable(path, 300) + "': cannot write: unknown extension; use " + list +
              " or -");
}

void checkResultsPath(const std::string& option, const std::string& path) {
  checkOutputPath(option, path);
  const std::string ext = detail::outputExtension(path, detail::resolveOutput(path));
  if (ext != ".csv" && ext != ".npy")
    throw Error(option + " '" + detail::printable(path, 300) + "': cannot write: " + detail::kResultsExtensionHint);
}

}  // namespace brdfcl
