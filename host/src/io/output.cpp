// The output-file layer every writer of brdfcl goes through: "-" is stdout, symlinks are followed
// to the file they name, FIFOs and devices are written in place, regular files atomically
// (a registered temporary beside the target, renamed into place), directories are refused.
#include "io/output.hpp"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <cstdio>
#include <cstdlib>
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

namespace {
// A new registered file named like a temporary in `dir`, created with `mode` (before the umask).
// With `like`, the file it will replace: the new one gets its owner (where this process may give
// it) and its permission bits, set before any byte is written, so that a private file never
// passes through a wider mode and a replaced output keeps who may read it.
std::string makeTemporary(const fs::path& dir, const struct stat* like, mode_t mode, const std::string& userPath) {
  const TemporaryOwner me = thisProcess();
  for (int attempt = 0;; ++attempt) {
    const std::string tmp = (dir / temporaryName(me)).string();
    // Registered before it exists, so that no signal can come between creation and registration.
    const bool registered = registerTemporary(tmp);
    // O_EXCL: never a file that is already there, whoever made it.
    const int fd = ::open(tmp.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, mode);
    if (fd >= 0) {
      if (like) {
        // The owner first: chown clears the set-user-ID and set-group-ID bits that fchmod sets.
        if ((like->st_uid != ::geteuid() || like->st_gid != ::getegid()) && ::fchown(fd, like->st_uid, like->st_gid) != 0)
          (void)::fchown(fd, static_cast<uid_t>(-1), like->st_gid);  // a group of ours, at least
        (void)::fchmod(fd, like->st_mode & 07777);  // on failure it stays 0600: narrower, never wider
      }
      ::close(fd);
      return tmp;
    }
    const int err = errno;
    if (registered) deregisterTemporary(tmp);
    if (err != EEXIST || attempt > 100) failErrno(userPath, err);
  }
}
}  // namespace

std::string createTemporary(const std::string& finalPath, const std::string& userPath) {
  const fs::path target(finalPath);
  removeStaleTemporaries(target.parent_path().string());
  struct stat old {};
  const bool replaces = ::stat(finalPath.c_str(), &old) == 0 && S_ISREG(old.st_mode);
  return makeTemporary(target.parent_path(), replaces ? &old : nullptr, replaces ? 0600 : 0666, userPath);
}

std::string createSpool(const std::string& userPath) {
  std::error_code ec;
  fs::path dir = fs::temp_directory_path(ec);
  if (ec) dir = "/tmp";
  removeStaleTemporaries(dir.string());
  // Only this process reads it back.
  return makeTemporary(dir, nullptr, 0600, userPath);
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

std::string npyHeader(std::size_t rows, std::size_t cols) {
  return npyHeader("(" + std::to_string(rows) + ", " + std::to_string(cols) + ")");
}

}  // namespace brdfcl::detail

namespace brdfcl {

namespace fs = std::filesystem;
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

namespace {
// What makes two command-line files one: device and inode of an existing regular file, else
// where a new output would be written. `known` is false for what is not compared.
struct FileIdentity {
  bool known = false, exists = false;
  dev_t device = 0;
  ino_t inode = 0;
  std::string path;
};

FileIdentity identify(const FileArgument& f) {
  FileIdentity id;
  if (f.path.empty() || f.path == "-" || f.path == "/dev/stdout") return id;
  struct stat st {};
  if (::stat(f.path.c_str(), &st) == 0) {
    if (!S_ISREG(st.st_mode)) return id;  // FIFOs and devices are streams, directories refused elsewhere
    id.known = id.exists = true;
    id.device = st.st_dev;
    id.inode = st.st_ino;
    return id;
  }
  if (!f.output) return id;  // a missing input fails when it is read
  detail::OutputTarget t;
  try {
    t = detail::resolveOutput(f.path);
  } catch (const Error&) {
    return id;  // checkOutputPath says what is wrong with it
  }
  if (t.kind != OutputKind::File) return id;
  const fs::path p(t.path);
  const std::string dir = p.parent_path().empty() ? "." : p.parent_path().string();
  char* real = ::realpath(dir.c_str(), nullptr);
  if (!real) return id;
  id.known = true;
  id.path = std::string(real) + "/" + p.filename().string();
  std::free(real);
  return id;
}
}  // namespace

void checkDistinctFiles(const std::vector<FileArgument>& files) {
  std::vector<FileIdentity> ids;
  for (const FileArgument& f : files) ids.push_back(identify(f));
  for (std::size_t j = 0; j < files.size(); ++j) {
    for (std::size_t i = 0; i < j; ++i) {
      const FileIdentity &a = ids[i], &b = ids[j];
      if (!a.known || !b.known || a.exists != b.exists || (!files[i].output && !files[j].output)) continue;
      if (a.exists ? a.device != b.device || a.inode != b.inode : a.path != b.path) continue;
      // The output first: it is what would destroy the other.
      const FileArgument& out = files[j].output ? files[j] : files[i];
      const FileArgument& other = files[j].output ? files[i] : files[j];
      throw Error(out.option + " '" + detail::printable(out.path, 300) + "' is the same file as " + other.option + " '" +
                  detail::printable(other.path, 300) + "'; " +
                  (other.output ? "give each output its own file" : "write the output elsewhere"));
    }
  }
}

void checkResultsPath(const std::string& option, const std::string& path) {
  checkOutputPath(option, path);
  const std::string ext = detail::outputExtension(path, detail::resolveOutput(path));
  if (ext != ".csv" && ext != ".npy")
    throw Error(option + " '" + detail::printable(path, 300) + "': cannot write: " + detail::kResultsExtensionHint);
}

}  // namespace brdfcl
