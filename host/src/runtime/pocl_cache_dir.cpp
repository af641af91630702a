// PoCL 3.1 fails its whole initialization ("no device") when it cannot create its kernel cache
// folder, asserts on an empty POCL_CACHE_DIR, and dies inside LLVM when that disk fills up while
// it writes a kernel. brdfcl checks the folder first and, when it would fail, gives PoCL a private
// temporary one for this process: kernels are then compiled on every run, but the run goes on.
#include "runtime/pocl_cache_dir.hpp"

#include <sys/stat.h>
#include <sys/statvfs.h>
#include <unistd.h>

#include <cerrno>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <string>
#include <vector>

#include <fmt/format.h>

#include "io/disk_cache.hpp"
#include "io/messages.hpp"

namespace brdfcl::detail {
namespace {

std::string temporaryFolder;  // set once, before any thread of PoCL's exists

void removeTemporaryFolder() {
  if (temporaryFolder.empty()) return;
  std::error_code ec;
  std::filesystem::remove_all(temporaryFolder, ec);  // does not follow links inside it
}

// Why PoCL could not use `folder` ("" when it can), creating it as PoCL would.
std::string problemWith(const std::string& folder) {
  std::error_code ec;
  std::filesystem::create_directories(folder, ec);
  if (ec) return fmt::format("cannot be created ({})", ec.message());
  struct stat st {};
  if (::stat(folder.c_str(), &st) != 0 || !S_ISDIR(st.st_mode)) return "is not a directory";
  if (::access(folder.c_str(), W_OK | X_OK) != 0) return fmt::format("is not writable ({})", std::strerror(errno));
  struct statvfs fs {};
  if (::statvfs(folder.c_str(), &fs) == 0) {
    const unsigned long long free = static_cast<unsigned long long>(fs.f_bavail) * fs.f_frsize;
    if (free < kPoclMinFreeBytes) return fmt::format("has only {} KiB free on its disk", free >> 10);
  }
  return "";
}

}  // namespace

std::string poclCacheFolder() {
  if (const char* d = std::getenv("POCL_CACHE_DIR")) return d;
  const char* kc = std::getenv("POCL_KERNEL_CACHE");
  const std::string leaf = kc && std::string(kc) == "0" ? "pocl/uncached" : "pocl/kcache";
  if (const char* x = std::getenv("XDG_CACHE_HOME"); x && *x) return std::string(x) + "/" + leaf;
  if (const char* h = std::getenv("HOME")) return std::string(h) + "/.cache/" + leaf;
  return "/tmp/" + leaf;
}

void preparePoclCacheFolder() {
  if (const char* d = std::getenv("POCL_CACHE_DIR"); d && !*d) ::unsetenv("POCL_CACHE_DIR");
  const std::string folder = poclCacheFolder();
  const std::string problem = problemWith(folder);
  if (problem.empty()) return;
  const char* t = std::getenv("TMPDIR");
  std::string pattern = std::string(t && *t ? t : "/tmp") + "/brdfcl-pocl-XXXXXX";
  std::vector<char> buf(pattern.begin(), pattern.end());
  buf.push_back('\0');
  if (!::mkdtemp(buf.data())) {
    cacheWarning(fmt::format("PoCL's kernel cache '{}' {}, and no temporary folder could be made ({}); set "
                             "POCL_CACHE_DIR to a writable folder",
                             printable(folder, 300), problem, std::strerror(errno)));
    return;
  }
  temporaryFolder = buf.data();
  std::atexit(removeTemporaryFolder);
  ::setenv("POCL_CACHE_DIR", temporaryFolder.c_str(), 1);
  cacheWarning(fmt::format("PoCL's kernel cache '{}' {}; using a temporary folder for this run, so kernels are "
                           "compiled on every run (set POCL_CACHE_DIR to a writable folder)",
                           printable(folder, 300), problem));
}

}  // namespace brdfcl::detail
