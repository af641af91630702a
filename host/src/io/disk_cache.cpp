// The on-disk cache shared by the sheen albedo bake, the environment preparation and the program
// binaries. Everything goes through one descriptor of the folder (opened without following a
// link, and used only when it is a directory of this user): entries are read only when they are
// regular files of this user, of a size the caller expects, whose header names the entry and
// whose checksum matches; they are written to a private temporary (O_EXCL, O_NOFOLLOW) and
// renamed into place. A failure of any kind costs a warning and a recompute, never the run.
#include "io/disk_cache.hpp"

#include <dirent.h>
#include <fcntl.h>
#include <signal.h>
#include <sys/stat.h>
#include <sys/uio.h>
#include <unistd.h>
#include <xxhash.h>

#include <algorithm>
#include <cctype>
#include <atomic>
#include <cerrno>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <functional>
#include <mutex>
#include <set>

#include <fmt/format.h>

#include "io/cache.hpp"
#include "brdfcl/error.hpp"
#include "io/messages.hpp"
#include "io/temporaries.hpp"

namespace brdfcl {
namespace {

std::mutex warningMutex;
std::function<void(const std::string&)> warningHandler;

}  // namespace

void setCacheWarningHandler(std::function<void(const std::string&)> handler) {
  std::lock_guard<std::mutex> lock(warningMutex);
  warningHandler = std::move(handler);
}

std::uint64_t cacheBudget() {
  const char* v = std::getenv("BRDFCL_CACHE_MAX");
  if (!v) return kDefaultCacheBudget;
  const std::string s = v;
  const auto bad = [&] {
    return Error(fmt::format("BRDFCL_CACHE_MAX '{}': not a size; give bytes with an optional K, M, G or T suffix "
                             "(e.g. 512M), or 0 to turn the cache off",
                             detail::printable(s)));
  };
  std::size_t i = 0;
  std::uint64_t n = 0;
  for (; i < s.size() && s[i] >= '0' && s[i] <= '9'; ++i) {
    if (n > (UINT64_MAX - 9) / 10) throw bad();
    n = n * 10 + std::uint64_t(s[i] - '0');
  }
  if (i == 0) throw bad();
  std::string unit = s.substr(i);
  int shift = 0;
  if (!unit.empty()) {
    const std::string units = "KMGT";
    const auto at = units.find(char(std::toupper(static_cast<unsigned char>(unit[0]))));
    if (at == std::string::npos) throw bad();
    shift = 10 * int(at + 1);
    unit = unit.substr(1);
    if (!unit.empty() && unit != "B" && unit != "iB") throw bad();
  }
  if (shift > 0 && n > (UINT64_MAX >> shift)) throw bad();
  return n << shift;
}

}  // namespace brdfcl

namespace brdfcl::detail {
namespace {

namespace fs = std::filesystem;

void warn(const std::string& text) { cacheWarning(text); }

// A folder's trouble is reported once per process, and a folder that failed a write is not
// written again: a full or read-only disk would otherwise warn for every entry.
std::mutex folderMutex;
std::set<std::string> warnedFolders, unwritableFolders;

void warnFolderOnce(const std::string& folder, const std::string& text) {
  {
    std::lock_guard<std::mutex> lock(folderMutex);
    if (!warnedFolders.insert(folder).second) return;
  }
  warn(text);
}

std::string quoted(const std::string& path) { return "'" + printable(path, 300) + "'"; }

struct Kind {
  const char* prefix;
  const char* suffix;
};
constexpr Kind kKinds[] = {
    {"sheen_e_", ".f32"}, {"env_", ".f32"}, {"ggx_dfg_", ".f32"}, {"aniso_dfg_", ".f32"}, {"program_", ".bin"}};

// The largest payload a read accepts when the caller does not know the size: program binaries
// are a few MB; anything near this is not one of ours.
constexpr std::size_t kMaxBytesPayload = std::size_t(256) << 20;

void putLE(unsigned char* p, std::uint64_t v, int bytes) {
  for (int i = 0; i < bytes; ++i) p[i] = static_cast<unsigned char>(v >> (8 * i));
}
std::uint64_t getLE(const unsigned char* p, int bytes) {
  std::uint64_t v = 0;
  for (int i = bytes - 1; i >= 0; --i) v = (v << 8) | p[i];
  return v;
}

constexpr char kMagic[8] = {'B', 'R', 'D', 'F', 'C', 'L', 'C', 'E'};

// The header with its checksum over bytes 16.. (the rest of the header, the key and the payload).
std::string entryHeader(std::string_view key, std::string_view payload) {
  std::string h(kCacheHeaderSize, '\0');
  auto* p = reinterpret_cast<unsigned char*>(h.data());
  std::memcpy(p, kMagic, 8);
  putLE(p + 16, kCacheEntryVersion, 4);
  putLE(p + 20, key.size(), 4);
  putLE(p + 24, payload.size(), 8);
  XXH3_state_t* state = XXH3_createState();
  if (!state) throw std::bad_alloc();
  XXH3_64bits_reset(state);
  XXH3_64bits_update(state, p + 16, kCacheHeaderSize - 16);
  XXH3_64bits_update(state, key.data(), key.size());
  XXH3_64bits_update(state, payload.data(), payload.size());
  putLE(p + 8, XXH3_64bits_digest(state), 8);
  XXH3_freeState(state);
  return h;
}

// One descriptor of the cache folder, so that every entry is looked up in the directory that
// was checked, whatever happens to the path afterwards.
class Folder {
 public:
  Folder(int fd, std::string path) : fd_(fd), path_(std::move(path)) {}
  ~Folder() {
    if (fd_ >= 0) ::close(fd_);
  }
  Folder(Folder&& o) noexcept : fd_(o.fd_), path_(std::move(o.path_)) { o.fd_ = -1; }
  Folder(const Folder&) = delete;
  Folder& operator=(const Folder&) = delete;
  Folder& operator=(Folder&&) = delete;
  int fd() const { return fd_; }
  const std::string& path() const { return path_; }
  std::string entry(const std::string& name) const { return path_ + "/" + name; }

 private:
  int fd_;
  std::string path_;
};

// Creates the missing folders of `dir`, private to the user (XDG's base directories are 0700).
int makeFolders(const fs::path& dir) {
  fs::path partial;
  for (const auto& part : dir) {
    partial /= part;
    if (part.empty() || part == "/") continue;
    if (::mkdir(partial.c_str(), 0700) != 0 && errno != EEXIST) return errno;
  }
  return 0;
}

// The folder, or nullopt with `problem` set ("" when there is simply no cache yet, or none at all).
std::optional<Folder> openFolder(bool create, std::string& problem) {
  problem.clear();
  const fs::path dir = cacheDirectory();
  if (dir.empty()) return std::nullopt;
  const std::string path = dir.string();
  if (create) {
    if (const int e = makeFolders(dir)) {
      problem = fmt::format("cannot create it: {}", std::strerror(e));
      return std::nullopt;
    }
  }
  const int fd = ::open(path.c_str(), O_RDONLY | O_DIRECTORY | O_NOFOLLOW | O_CLOEXEC);
  if (fd < 0) {
    const int e = errno;
    if (e == ENOENT && !create) return std::nullopt;
    struct stat own {};
    problem = (e == ENOTDIR || e == ELOOP) && ::lstat(path.c_str(), &own) == 0 && !S_ISDIR(own.st_mode)
                  ? std::string("not a directory (a file, or a link)")
                  : fmt::format("cannot open it: {}", std::strerror(e));
    return std::nullopt;
  }
  struct stat st {};
  if (::fstat(fd, &st) != 0 || !S_ISDIR(st.st_mode)) {
    ::close(fd);
    problem = "not a directory";
    return std::nullopt;
  }
  if (st.st_uid != ::geteuid()) {
    ::close(fd);
    problem = fmt::format("owned by uid {}, not by this user (uid {})", st.st_uid, ::geteuid());
    return std::nullopt;
  }
  return Folder(fd, path);
}

// The folder for reading (nullopt when there is none yet) or writing (created if missing); its
// trouble is one warning. A zero budget turns the cache off.
std::optional<Folder> usableFolder(bool create) {
  if (cacheBudget() == 0) return std::nullopt;
  std::string problem;
  auto folder = openFolder(create, problem);
  if (!folder && !problem.empty()) {
    const std::string path = cacheDirectory().string();
    warnFolderOnce(path, fmt::format("cache folder {}: {}; running without the cache", quoted(path), problem));
  }
  return folder;
}

void removeEntry(const Folder& f, const std::string& name, bool directory) {
  ::unlinkat(f.fd(), name.c_str(), directory ? AT_REMOVEDIR : 0);
}

void badEntry(const Folder& f, const std::string& name, const std::string& why, bool directory = false) {
  removeEntry(f, name, directory);
  warn(fmt::format("cache entry {} {}; removed, computing it again", quoted(f.entry(name)), why));
}

// The payload of entry `name` when it is intact and its size is within [minPayload, maxPayload].
std::optional<std::string> readEntry(const Folder& f, const std::string& name, std::size_t minPayload,
                                     std::size_t maxPayload) {
  // O_NONBLOCK: a FIFO in the entry's place must not block the open.
  const int fd = ::openat(f.fd(), name.c_str(), O_RDONLY | O_NOFOLLOW | O_NONBLOCK | O_CLOEXEC);
  if (fd < 0) {
    const int e = errno;
    if (e == ENOENT) return std::nullopt;
    badEntry(f, name, e == ELOOP ? "is a link" : fmt::format("cannot be opened ({})", std::strerror(e)));
    return std::nullopt;
  }
  struct Closer {
    int fd;
    ~Closer() { ::close(fd); }
  } closer{fd};
  struct stat st {};
  if (::fstat(fd, &st) != 0) {
    badEntry(f, name, fmt::format("cannot be read ({})", std::strerror(errno)));
    return std::nullopt;
  }
  if (!S_ISREG(st.st_mode)) {
    badEntry(f, name, S_ISDIR(st.st_mode) ? "is a directory" : "is not a regular file", S_ISDIR(st.st_mode));
    return std::nullopt;
  }
  if (st.st_uid != ::geteuid()) {
    badEntry(f, name, fmt::format("is owned by uid {}, not by this user", st.st_uid));
    return std::nullopt;
  }
  const std::uint64_t fixed = kCacheHeaderSize + name.size();
  const std::uint64_t size = std::uint64_t(st.st_size);
  if (size < fixed + minPayload || size > fixed + maxPayload) {
    badEntry(f, name, fmt::format("holds {} bytes, not a whole entry", size));
    return std::nullopt;
  }
  std::string bytes(std::size_t(size), '\0');
  for (std::size_t done = 0; done < bytes.size();) {
    const ssize_t n = ::pread(fd, bytes.data() + done, bytes.size() - done, off_t(done));
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) {
      badEntry(f, name, n < 0 ? fmt::format("cannot be read ({})", std::strerror(errno)) : std::string("is truncated"));
      return std::nullopt;
    }
    done += std::size_t(n);
  }
  const auto payload = parseCacheEntry(bytes, name);
  if (!payload) {
    badEntry(f, name, "fails its check (corrupt, or not this entry)");
    return std::nullopt;
  }
  // Marked at most once an hour: a use order to the hour is all pruning needs, and a process
  // start then costs no metadata write per program.
  const auto now = std::chrono::system_clock::now().time_since_epoch();
  const auto marked = std::chrono::seconds(st.st_mtim.tv_sec);
  if (now - marked > kUseMarkInterval) ::futimens(fd, nullptr);
  // The payload moved to the front of the pages already read, rather than copied into fresh ones
  // (a program binary is megabytes: each copy costs its page faults at start-up).
  const std::size_t at = std::size_t(payload->data() - bytes.data()), n = payload->size();
  bytes.erase(0, at);
  bytes.resize(n);
  return bytes;
}

struct Listed {
  std::string name;
  std::size_t kind = 0;
  std::uint64_t bytes = 0;
  struct timespec mtime {};
  bool directory = false;
};

// The folder's own entries (regular files or not; links are not followed). Temporaries that dead
// processes of this host left are removed on the way when `sweep` is set.
std::vector<Listed> listEntries(const Folder& f, bool sweep) {
  std::vector<Listed> out;
  const int dfd = ::openat(f.fd(), ".", O_RDONLY | O_DIRECTORY | O_CLOEXEC);
  if (dfd < 0) return out;
  DIR* d = ::fdopendir(dfd);
  if (!d) {
    ::close(dfd);
    return out;
  }
  const TemporaryOwner self = thisProcess();
  while (const dirent* e = ::readdir(d)) {
    const std::string name = e->d_name;
    Listed l;
    if (!isCacheEntryName(name, &l.kind)) {
      if (sweep && isStaleTemporary(f.fd(), name.c_str(), self)) ::unlinkat(f.fd(), name.c_str(), 0);
      continue;
    }
    struct stat st {};
    if (::fstatat(f.fd(), name.c_str(), &st, AT_SYMLINK_NOFOLLOW) != 0) continue;
    l.name = name;
    l.bytes = S_ISREG(st.st_mode) ? std::uint64_t(st.st_size) : 0;
    l.mtime = st.st_mtim;
    l.directory = S_ISDIR(st.st_mode);
    out.push_back(std::move(l));
  }
  ::closedir(d);
  return out;
}

bool olderFirst(const Listed& a, const Listed& b) {
  if (a.mtime.tv_sec != b.mtime.tv_sec) return a.mtime.tv_sec < b.mtime.tv_sec;
  if (a.mtime.tv_nsec != b.mtime.tv_nsec) return a.mtime.tv_nsec < b.mtime.tv_nsec;
  return a.name < b.name;
}

// Removes the least recently used entries until the rest fit `budget`; `keep` (just stored) last.
void pruneToBudget(const Folder& f, std::uint64_t budget, const std::string& keep) {
  auto entries = listEntries(f, true);
  std::uint64_t total = 0;
  for (const auto& e : entries) total += e.bytes;
  if (total <= budget) return;
  std::sort(entries.begin(), entries.end(), olderFirst);
  std::stable_partition(entries.begin(), entries.end(), [&](const Listed& e) { return e.name != keep; });
  for (const auto& e : entries) {
    if (total <= budget) break;
    if (e.directory) continue;
    if (::unlinkat(f.fd(), e.name.c_str(), 0) == 0) total -= e.bytes;
  }
}

void writeFailed(const Folder& f, int err) {
  {
    std::lock_guard<std::mutex> lock(folderMutex);
    unwritableFolders.insert(f.path());
  }
  warnFolderOnce(f.path(), fmt::format("cannot write to the cache folder {}: {}; running without storing to the cache",
                                       quoted(f.path()), std::strerror(err)));
}

// Writes header, key and payload to a new private temporary and renames it to `name`.
int writeEntry(const Folder& f, const std::string& name, std::string_view payload) {
  const std::string header = entryHeader(name, payload);
  const std::string tmp = temporaryName(thisProcess());
  const std::string tmpPath = f.entry(tmp);
  const bool registered = registerTemporary(tmpPath);
  const int fd = ::openat(f.fd(), tmp.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_NOFOLLOW | O_CLOEXEC, 0600);
  int err = fd < 0 ? errno : 0;
  if (fd >= 0) {
    const std::string_view parts[] = {header, name, payload};
    for (const auto part : parts) {
      for (std::size_t done = 0; err == 0 && done < part.size();) {
        const ssize_t n = ::write(fd, part.data() + done, part.size() - done);
        if (n < 0 && errno == EINTR) continue;
        if (n <= 0) err = n < 0 ? errno : EIO;
        else done += std::size_t(n);
      }
    }
    if (::close(fd) != 0 && err == 0) err = errno;
    if (err == 0 && ::renameat(f.fd(), tmp.c_str(), f.fd(), name.c_str()) != 0) err = errno;
    if (err != 0) ::unlinkat(f.fd(), tmp.c_str(), 0);
  }
  if (registered) deregisterTemporary(tmpPath);
  return err;
}

void storeCached(const std::string& name, std::string_view payload) {
  const std::uint64_t budget = cacheBudget();
  if (budget == 0) return;
  auto folder = usableFolder(true);
  if (!folder) return;
  {
    std::lock_guard<std::mutex> lock(folderMutex);
    if (unwritableFolders.count(folder->path())) return;
  }
  const std::uint64_t size = kCacheHeaderSize + name.size() + payload.size();
  if (size > budget) {
    warn(fmt::format("{} ({} bytes) is larger than the cache budget ({} bytes, BRDFCL_CACHE_MAX); not cached",
                     quoted(folder->entry(name)), size, budget));
    return;
  }
  if (const int err = writeEntry(*folder, name, payload)) {
    writeFailed(*folder, err);
    return;
  }
  pruneToBudget(*folder, budget, name);
}

}  // namespace

void cacheWarning(const std::string& text) {
  std::lock_guard<std::mutex> lock(warningMutex);
  if (warningHandler) warningHandler(text);
  else std::fprintf(stderr, "brdfcl: warning: %s\n", text.c_str());
}

fs::path cacheDirectory() {
  if (const char* x = std::getenv("XDG_CACHE_HOME"); x && *x) return fs::path(x) / "brdfcl";
  if (const char* h = std::getenv("HOME"); h && *h) return fs::path(h) / ".cache" / "brdfcl";
  return {};
}

std::uint64_t contentHash(std::string_view bytes, std::uint64_t seed) {
  std::uint64_t h = seed;
  for (const unsigned char c : bytes) {
    h ^= c;
    h *= 0x100000001b3ull;
  }
  return h;
}

std::uint64_t contentHash(const std::vector<float>& values, std::uint64_t seed) {
  return contentHash(std::string_view(reinterpret_cast<const char*>(values.data()), values.size() * sizeof(float)), seed);
}

std::string encodeCacheEntry(std::string_view key, std::string_view payload) {
  std::string out = entryHeader(key, payload);
  out.append(key);
  out.append(payload);
  return out;
}

std::optional<std::string_view> parseCacheEntry(std::string_view bytes, std::string_view key) {
  if (bytes.size() < kCacheHeaderSize || std::memcmp(bytes.data(), kMagic, 8) != 0) return std::nullopt;
  const auto* p = reinterpret_cast<const unsigned char*>(bytes.data());
  if (getLE(p + 16, 4) != kCacheEntryVersion) return std::nullopt;
  const std::uint64_t keySize = getLE(p + 20, 4), payloadSize = getLE(p + 24, 8);
  if (keySize != key.size() || keySize > kCacheKeyMax) return std::nullopt;
  const std::size_t rest = bytes.size() - kCacheHeaderSize;
  if (keySize > rest || payloadSize != rest - keySize) return std::nullopt;
  if (bytes.substr(kCacheHeaderSize, key.size()) != key) return std::nullopt;
  if (XXH3_64bits(bytes.data() + 16, bytes.size() - 16) != getLE(p + 8, 8)) return std::nullopt;
  return bytes.substr(kCacheHeaderSize + key.size());
}

bool isCacheEntryName(const std::string& name, std::size_t* kind) {
  if (name.size() > 255) return false;
  for (std::size_t k = 0; k < std::size(kKinds); ++k) {
    const std::string_view prefix = kKinds[k].prefix, suffix = kKinds[k].suffix;
    if (name.size() <= prefix.size() + suffix.size() || name.compare(0, prefix.size(), prefix) != 0 ||
        name.compare(name.size() - suffix.size(), suffix.size(), suffix) != 0)
      continue;
    const bool plain = std::all_of(name.begin(), name.end(), [](char c) {
      return (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') || c == '_' || c == '.' ||
             c == '-';
    });
    if (!plain) return false;
    if (kind) *kind = k;
    return true;
  }
  return false;
}

bool loadCachedFloats(const std::string& name, std::vector<float>& out) {
  const auto folder = usableFolder(false);
  if (!folder) return false;
  const std::size_t bytes = out.size() * sizeof(float);
  const auto payload = readEntry(*folder, name, bytes, bytes);
  if (!payload) return false;
  std::memcpy(out.data(), payload->data(), bytes);
  return true;
}

void storeCachedFloats(const std::string& name, const std::vector<float>& values) {
  storeCached(name, std::string_view(reinterpret_cast<const char*>(values.data()), values.size() * sizeof(float)));
}

std::vector<unsigned char> loadCachedBytes(const std::string& name) {
  const auto folder = usableFolder(false);
  if (!folder) return {};
  const auto payload = readEntry(*folder, name, 1, kMaxBytesPayload);
  if (!payload) return {};
  return std::vector<unsigned char>(payload->begin(), payload->end());
}

std::string loadCachedPayload(const std::string& name) {
  const auto folder = usableFolder(false);
  if (!folder) return {};
  auto payload = readEntry(*folder, name, 1, kMaxBytesPayload);
  return payload ? std::move(*payload) : std::string();
}

void storeCachedBytes(const std::string& name, const std::vector<unsigned char>& bytes) {
  storeCached(name, std::string_view(reinterpret_cast<const char*>(bytes.data()), bytes.size()));
}

void pruneCached(const std::string& prefix, std::size_t keep) {
  std::string problem;
  const auto folder = openFolder(false, problem);
  if (!folder) return;
  auto entries = listEntries(*folder, false);
  entries.erase(std::remove_if(entries.begin(), entries.end(),
                               [&](const Listed& e) { return e.directory || e.name.rfind(prefix, 0) != 0; }),
                entries.end());
  if (entries.size() <= keep) return;
  std::sort(entries.begin(), entries.end(), [](const Listed& a, const Listed& b) { return olderFirst(b, a); });
  for (std::size_t i = keep; i < entries.size(); ++i) ::unlinkat(folder->fd(), entries[i].name.c_str(), 0);
}

}  // namespace brdfcl::detail

namespace brdfcl {

const std::vector<std::string>& cacheKinds() {
  static const std::vector<std::string> kinds = [] {
    std::vector<std::string> k;
    for (const auto& kind : detail::kKinds) {
      std::string prefix = kind.prefix;
      prefix.pop_back();
      k.push_back(prefix);
    }
    return k;
  }();
  return kinds;
}

CacheUsage cacheUsage() {
  CacheUsage u;
  u.budget = cacheBudget();
  u.folder = detail::cacheDirectory().string();
  for (const auto& k : cacheKinds()) u.kinds.push_back({k, 0, 0});
  const auto folder = detail::openFolder(false, u.problem);
  if (!folder) return u;
  for (const auto& e : detail::listEntries(*folder, false)) {
    if (e.directory) continue;
    ++u.kinds[e.kind].entries;
    u.kinds[e.kind].bytes += e.bytes;
    ++u.entries;
    u.bytes += e.bytes;
  }
  return u;
}

CacheCleared clearCache() {
  CacheCleared c;
  c.folder = detail::cacheDirectory().string();
  std::string problem;
  const auto folder = detail::openFolder(false, problem);
  if (!folder) {
    if (problem.empty()) return c;
    throw Error(ErrorKind::Environment, fmt::format("cache folder {}: {}; nothing removed", detail::quoted(c.folder), problem));
  }
  for (const auto& e : detail::listEntries(*folder, true)) {
    if (e.directory) continue;
    if (::unlinkat(folder->fd(), e.name.c_str(), 0) != 0) continue;
    ++c.entries;
    c.bytes += e.bytes;
  }
  return c;
}

}  // namespace brdfcl
