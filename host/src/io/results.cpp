// Result output (r,g,b as CSV or .npy), whole or a chunk at a time, and writeAtomically, which
// every output of brdfcl goes through so that a failed run never leaves a partial file behind.
// CSV formatting runs on several threads; writes are plain POSIX calls so every errno surfaces.
#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <cerrno>
#include <charconv>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <stdexcept>
#include <string>
#include <vector>

#include "brdfcl/error.hpp"
#include "brdfcl/io.hpp"
#include "io/messages.hpp"
#include "io/rows.hpp"

static_assert(__BYTE_ORDER__ == __ORDER_LITTLE_ENDIAN__, "the NPY writer copies little-endian floats as-is");

namespace brdfcl {
namespace {

using detail::printable;

std::atomic<unsigned> tmpCounter{0};

// Creates an empty temporary beside `path` (same directory, so rename() is atomic;
// dot-prefixed, so directory listings ignore it) and returns its name. Fails early, before a
// possibly long write, on anything that would make the final rename fail.
std::string createTemporary(const std::string& path) {
  namespace fs = std::filesystem;
  const std::string shown = printable(path, 300);
  const fs::path target(path);
  const std::string fileName = target.filename().string();
  if (fileName.empty() || fileName == "." || fileName == "..")
    throw Error("cannot write '" + shown + "': not a file name");
  struct stat st {};
  if (::stat(path.c_str(), &st) == 0 && S_ISDIR(st.st_mode))
    throw Error("cannot write '" + shown + "': " + std::strerror(EISDIR));
  const fs::path dir = target.parent_path();
  const std::string stem = "." + fileName.substr(0, 200) + ".tmp." + std::to_string(::getpid()) + ".";
  for (int attempt = 0;; ++attempt) {
    std::string tmp = (dir / (stem + std::to_string(tmpCounter.fetch_add(1)))).string();
    // O_EXCL: a stale temporary of a crashed run with the same pid must not be reused.
    const int fd = ::open(tmp.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, 0666);
    if (fd >= 0) {
      ::close(fd);
      return tmp;
    }
    if (errno != EEXIST || attempt > 100) throw Error("cannot write '" + shown + "': " + std::strerror(errno));
  }
}

void renameIntoPlace(const std::string& tmp, const std::string& path) {
  if (std::rename(tmp.c_str(), path.c_str()) != 0)
    throw Error("cannot write '" + printable(path, 300) + "': " + std::strerror(errno));
}

// Unbuffered POSIX writes through our own buffer: every failure (ENOSPC, EFBIG, EIO at close)
// surfaces as an errno that we turn into a message naming the user's path, not the temporary.
class OutputFile {
 public:
  OutputFile(const std::string& tmpPath, const std::string& userPath) : userPath_(userPath) {
    fd_ = ::open(tmpPath.c_str(), O_WRONLY | O_TRUNC | O_CLOEXEC);
    if (fd_ < 0) fail(errno);
    buf_.resize(1 << 20);
  }
  ~OutputFile() {
    if (fd_ >= 0) ::close(fd_);
  }
  OutputFile(const OutputFile&) = delete;
  OutputFile& operator=(const OutputFile&) = delete;

  void append(const void* p, std::size_t n) {
    if (n == 0) return;  // p may be the null data() of an empty vector
    if (n > buf_.size() - used_) {
      flush();
      writeAll(static_cast<const char*>(p), n);
      return;
    }
    std::memcpy(buf_.data() + used_, p, n);
    used_ += n;
  }
  // Overwrites bytes already appended (the NPY header once the row count is known).
  void patch(std::size_t offset, const void* p, std::size_t n) {
    flush();
    const char* c = static_cast<const char*>(p);
    while (n > 0) {
      const ssize_t w = ::pwrite(fd_, c, n, static_cast<off_t>(offset));
      if (w < 0) {
        if (errno == EINTR) continue;
        fail(errno);
      }
      c += w;
      offset += static_cast<std::size_t>(w);
      n -= static_cast<std::size_t>(w);
    }
  }
  void close() {
    flush();
    const int fd = fd_;
    fd_ = -1;
    if (::close(fd) != 0) fail(errno);
  }

 private:
  void flush() {
    writeAll(buf_.data(), used_);
    used_ = 0;
  }
  void writeAll(const char* p, std::size_t n) {
    while (n > 0) {
      const ssize_t w = ::write(fd_, p, n);
      if (w < 0) {
        if (errno == EINTR) continue;
        fail(errno);
      }
      p += w;
      n -= static_cast<std::size_t>(w);
    }
  }
  [[noreturn]] void fail(int err) const {
    throw Error("cannot write '" + printable(userPath_, 300) + "': " + std::strerror(err));
  }

  std::string userPath_;
  int fd_ = -1;
  std::vector<char> buf_;
  std::size_t used_ = 0;
};

// NPY v1.0 header for `rows` x 3 float32. Magic (6) + version (2) + length (2) + dict + '\n' is
// padded to 128 bytes whatever the row count (up to 20 digits), so a streamed file can reserve
// it before knowing the count and patch it in place afterwards.
std::string npyHeader(std::size_t rows) {
  constexpr std::size_t kTotal = 128;
  std::string dict = "{'descr': '<f4', 'fortran_order': False, 'shape': (" + std::to_string(rows) + ", 3), }";
  dict.append(kTotal - 10 - dict.size() - 1, ' ');
  dict += '\n';
  const std::size_t len = dict.size();
  const char prefix[10] = {
      '\x93', 'N', 'U', 'M', 'P', 'Y', 1, 0, static_cast<char>(len & 0xff), static_cast<char>(len >> 8)};
  return std::string(prefix, sizeof prefix) + dict;
}

// Appends `rows` CSV rows in rounds of `batch` rows per worker: formatting runs in parallel,
// writing in file order, and memory stays bounded whatever the row count.
void appendCsvRows(OutputFile& f, const float* rgb, std::size_t rows, std::vector<std::vector<char>>& text) {
  constexpr std::size_t batch = 1 << 16;
  constexpr std::size_t maxValue = 24;  // "%.9g" of a float needs at most 15 characters
  const std::size_t workers = detail::workerCount(rows * 3 * 12);
  if (text.size() < workers) text.resize(workers);
  for (auto& t : text) t.resize(batch * 3 * maxValue);
  std::vector<std::size_t> used(workers);
  for (std::size_t start = 0; start < rows; start += workers * batch) {
    detail::parallelFor(workers, [&](std::size_t w) {
      const std::size_t first = std::min(rows, start + w * batch), last = std::min(rows, first + batch);
      char* p = text[w].data();
      for (std::size_t i = 3 * first; i < 3 * last; i += 3) {
        for (int c = 0; c < 3; ++c) {
          // 9 significant digits round-trip every float; chars_format::general is printf's %g.
          p = std::to_chars(p, p + maxValue, rgb[i + c], std::chars_format::general, 9).ptr;
          *p++ = c < 2 ? ',' : '\n';
        }
      }
      used[w] = static_cast<std::size_t>(p - text[w].data());
    });
    for (std::size_t w = 0; w < workers; ++w) f.append(text[w].data(), used[w]);
  }
}

}  // namespace

struct ResultWriter::Impl {
  std::string path, tmp;
  bool npy = false, committed = false;
  std::size_t rows = 0;
  std::unique_ptr<OutputFile> file;
  std::vector<std::vector<char>> csvText;  // formatting buffers, kept across chunks
};

ResultWriter::ResultWriter(const std::string& path) : impl_(std::make_unique<Impl>()) {
  impl_->path = path;
  impl_->npy = detail::hasNpyExtension(path);
  impl_->tmp = createTemporary(path);
  try {
    impl_->file = std::make_unique<OutputFile>(impl_->tmp, path);
    if (impl_->npy) {
      const std::string h = npyHeader(0);  // patched by commit()
      impl_->file->append(h.data(), h.size());
    } else {
      impl_->file->append("r,g,b\n", 6);
    }
  } catch (...) {
    impl_->file.reset();
    ::unlink(impl_->tmp.c_str());
    throw;
  }
}

ResultWriter::~ResultWriter() {
  if (impl_->committed) return;
  impl_->file.reset();
  ::unlink(impl_->tmp.c_str());
}

std::size_t ResultWriter::rows() const { return impl_->rows; }

void ResultWriter::append(const float* rgb, std::size_t rows) {
  if (impl_->committed) throw std::logic_error("ResultWriter::append after commit");
  if (impl_->npy)
    impl_->file->append(rgb, rows * 3 * sizeof(float));
  else
    appendCsvRows(*impl_->file, rgb, rows, impl_->csvText);
  impl_->rows += rows;
}

void ResultWriter::commit() {
  if (impl_->committed) throw std::logic_error("ResultWriter::commit twice");
  if (impl_->npy) {
    const std::string h = npyHeader(impl_->rows);
    impl_->file->patch(0, h.data(), h.size());
  }
  impl_->file->close();
  impl_->file.reset();
  renameIntoPlace(impl_->tmp, impl_->path);
  impl_->committed = true;
}

void writeResults(const std::string& path, const std::vector<float>& rgb) {
  if (rgb.size() % 3 != 0) throw std::invalid_argument("writeResults: rgb.size() is not a multiple of 3");
  ResultWriter w(path);
  w.append(rgb.data(), rgb.size() / 3);
  w.commit();
}

void writeAtomically(const std::string& path, const std::function<void(const std::string& tmpPath)>& write) {
  const std::string tmp = createTemporary(path);
  try {
    write(tmp);
    renameIntoPlace(tmp, path);
  } catch (...) {
    ::unlink(tmp.c_str());
    throw;
  }
}

void checkOutputPath(const std::string& option, const std::string& path) {
  namespace fs = std::filesystem;
  const std::string head = option + " '" + printable(path, 300) + "': cannot write: ";
  struct stat st {};
  if (::stat(path.c_str(), &st) == 0) {
    if (S_ISDIR(st.st_mode)) throw Error(head + "it is a directory; name a file inside it");
    if (::access(path.c_str(), W_OK) != 0) throw Error(head + std::strerror(errno));
  }
  const fs::path dir = fs::path(path).parent_path();
  const std::string d = dir.empty() ? "." : dir.string();
  if (::stat(d.c_str(), &st) != 0) throw Error(head + std::strerror(errno));
  if (!S_ISDIR(st.st_mode)) throw Error(head + "'" + printable(d, 300) + "' is not a directory");
  if (::access(d.c_str(), W_OK | X_OK) != 0) throw Error(head + std::strerror(errno));
}

}  // namespace brdfcl
