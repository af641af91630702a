// Result output (r,g,b as CSV or .npy), whole or a chunk at a time, through the output layer
// (io/output.hpp): atomic for files, streamed to stdout, FIFOs and devices.
// CSV formatting runs on several threads; writes are plain POSIX calls so every errno surfaces.
#include <fcntl.h>
#include <sys/stat.h>
#include <sys/vfs.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <cerrno>
#include <charconv>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <stdexcept>
#include <string>
#include <vector>

#include "brdfcl/error.hpp"
#include "brdfcl/io.hpp"
#include "io/messages.hpp"
#include "io/output.hpp"
#include "io/rows.hpp"

static_assert(__BYTE_ORDER__ == __ORDER_LITTLE_ENDIAN__, "the NPY writer copies little-endian floats as-is");

namespace brdfcl {
namespace {

using detail::printable;

// Unbuffered POSIX writes through our own buffer: every failure (ENOSPC, EFBIG, EIO at close)
// surfaces as an errno that we turn into a message naming the user's path, not the temporary.
//
// A `direct` file (an NPY result going to a regular file) writes its whole blocks with O_DIRECT
// from a page-aligned buffer, where the filesystem allows it: the result then goes from our one
// reused buffer to the disk, without a copy into fresh page-cache pages. Those pages are what
// made NPY output slow (docs/performance.md, "The library and files at kernel speed"): writing into
// them costs a copy and, on a VM that hands freed memory back to its host, a fault per page. The
// tail and the header patch go through the page cache; other filesystems (tmpfs, NFS) get
// buffered writes throughout.
class OutputFile {
 public:
  static constexpr std::size_t kBuffer = std::size_t(1) << 20;  // a multiple of any block size
  static constexpr std::size_t kAlign = 4096;                   // O_DIRECT's memory and offset alignment

  // Writes `fd`, which it closes when it `owns` it (not stdout's).
  OutputFile(int fd, bool owns, const std::string& userPath, bool direct = false)
      : userPath_(userPath), fd_(fd), owns_(owns), buf_(static_cast<char*>(std::aligned_alloc(kAlign, kBuffer))) {
    if (!buf_) throw Error(ErrorKind::Memory, "out of host memory allocating an output buffer for '" + printable(userPath_, 300) + "'");
    if (direct && onLocalDisk(fd_)) {
      const int flags = ::fcntl(fd_, F_GETFL);
      direct_ = flags >= 0 && ::fcntl(fd_, F_SETFL, flags | O_DIRECT) == 0;
    }
  }
  ~OutputFile() {
    if (fd_ >= 0 && owns_) ::close(fd_);
    std::free(buf_);
  }
  OutputFile(const OutputFile&) = delete;
  OutputFile& operator=(const OutputFile&) = delete;

  void append(const void* p, std::size_t n) {
    if (n == 0) return;  // p may be the null data() of an empty vector
    appended_ += n;
    const char* c = static_cast<const char*>(p);
    if (!direct_ && n > kBuffer - used_) {
      flush();
      writeAll(c, n);
      return;
    }
    while (n > 0) {
      const std::size_t take = std::min(n, kBuffer - used_);
      std::memcpy(buf_ + used_, c, take);
      used_ += take;
      c += take;
      n -= take;
      if (used_ == kBuffer) flush();
    }
  }
  // append() of p[0, n) with p[-kAlign, 0) free to use: when p lies at its file offset modulo
  // kAlign, the partial block buffered so far is put in front of it and the whole blocks go to
  // the disk from p itself; the partial block at the end is kept for the next append.
  void appendInPlace(char* p, std::size_t n) {
    const std::size_t carry = used_ % kAlign;
    if (!direct_ || n < kAlign || (reinterpret_cast<std::uintptr_t>(p) - carry) % kAlign != 0) {
      append(p, n);
      return;
    }
    flushWholeBlocks();
    if (!direct_) {
      append(p, n);
      return;
    }
    appended_ += n;
    char* start = p - carry;
    std::memcpy(start, buf_, carry);
    const std::size_t total = carry + n, whole = total / kAlign * kAlign;
    const std::size_t done = writeDirect(start, whole);
    writeAll(start + done, whole - done);
    used_ = total - whole;
    std::memcpy(buf_, start + whole, used_);
  }
  std::size_t appended() const { return appended_; }
  // Overwrites bytes already appended (the NPY header once the row count is known).
  void patch(std::size_t offset, const void* p, std::size_t n) {
    flush();
    buffered();
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
    if (owns_ && ::close(fd) != 0) fail(errno);
  }

 private:
  // Everything buffered: with O_DIRECT its whole blocks (all of a full buffer) go straight to
  // the disk, and the partial block left at the end through the page cache.
  void flush() {
    std::size_t n = used_;
    const char* p = buf_;
    if (direct_) {
      const std::size_t whole = n / kAlign * kAlign;
      const std::size_t done = writeDirect(p, whole);
      p += done;
      n -= done;
      if (n > 0) buffered();
    }
    writeAll(p, n);
    used_ = 0;
  }
  // The whole blocks of the buffer, keeping its partial block at the front.
  void flushWholeBlocks() {
    const std::size_t whole = used_ / kAlign * kAlign;
    if (whole == 0) return;
    const std::size_t done = writeDirect(buf_, whole);
    writeAll(buf_ + done, whole - done);
    used_ -= whole;
    std::memmove(buf_, buf_ + whole, used_);
  }
  // Whole blocks with O_DIRECT; returns how much was written before the filesystem declined
  // (EINVAL: no O_DIRECT here) or wrote short (a size limit, a full disk), after which this file
  // writes through the page cache, where the error, if any, is reported.
  std::size_t writeDirect(const char* p, std::size_t n) {
    std::size_t done = 0;
    while (direct_ && done < n) {
      const ssize_t w = ::write(fd_, p + done, n - done);
      if (w < 0 && errno == EINTR) continue;
      if (w < 0 && errno != EINVAL) fail(errno);
      if (w <= 0 || static_cast<std::size_t>(w) % kAlign != 0) buffered();
      if (w > 0) done += static_cast<std::size_t>(w);
    }
    return done;
  }
  // ext4, XFS and btrfs on a local disk: there O_DIRECT streams at the disk's speed. A network
  // filesystem would make every direct write a synchronous round trip, so the rest stay buffered.
  static bool onLocalDisk(int fd) {
    struct statfs fs {};
    if (::fstatfs(fd, &fs) != 0) return false;
    constexpr long kExt4 = 0xEF53, kXfs = 0x58465342, kBtrfs = 0x9123683E;
    const long type = static_cast<long>(fs.f_type);
    return type == kExt4 || type == kXfs || type == kBtrfs;
  }
  void buffered() {
    if (!direct_) return;
    direct_ = false;
    const int flags = ::fcntl(fd_, F_GETFL);
    if (flags < 0 || ::fcntl(fd_, F_SETFL, flags & ~O_DIRECT) != 0) fail(errno);
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
  bool owns_ = true;
  bool direct_ = false;
  char* buf_ = nullptr;
  std::size_t used_ = 0;
  std::size_t appended_ = 0;  // bytes appended in all, the file offset the next append starts at
};

std::string npyHeader(std::size_t rows) { return detail::npyHeader(rows, 3); }

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
  std::string path;
  detail::OutputTarget target;
  std::string tmp;  // the temporary beside a File target, or the spool of NPY to a stream; else empty
  bool npy = false, committed = false, header = true;
  std::size_t rows = 0;
  std::unique_ptr<OutputFile> file;
  std::vector<std::vector<char>> csvText;  // formatting buffers, kept across chunks
};

ResultWriter::ResultWriter(const std::string& path) : ResultWriter(path, "", true) {}

ResultWriter::ResultWriter(const std::string& path, const std::string& format, bool header)
    : impl_(std::make_unique<Impl>()) {
  impl_->path = path;
  impl_->header = header;
  impl_->target = detail::resolveOutput(path);
  const std::string ext = format.empty() ? detail::outputExtension(path, impl_->target) : format;
  if (ext != ".csv" && ext != ".npy")
    throw Error("cannot write '" + printable(path, 300) + "': " + detail::kResultsExtensionHint);
  impl_->npy = ext == ".npy";
  const bool toFile = impl_->target.kind == detail::OutputKind::File;
  try {
    if (toFile || impl_->npy) {
      // NPY's row count is patched into its header at commit: a stream gets a spooled copy.
      impl_->tmp = toFile ? detail::createTemporary(impl_->target.path, path) : detail::createSpool(path);
      const int fd = ::open(impl_->tmp.c_str(), O_WRONLY | O_TRUNC | O_CLOEXEC);
      if (fd < 0) throw Error("cannot write '" + printable(path, 300) + "': " + std::strerror(errno));
      impl_->file = std::make_unique<OutputFile>(fd, true, path, toFile && impl_->npy);
    } else {
      const int fd = detail::openStream(impl_->target, path);
      impl_->file = std::make_unique<OutputFile>(fd, impl_->target.kind == detail::OutputKind::Stream, path);
    }
    if (header && impl_->npy) {
      const std::string h = npyHeader(0);  // patched by commit()
      impl_->file->append(h.data(), h.size());
    } else if (header) {
      impl_->file->append("r,g,b\n", 6);
    }
  } catch (...) {
    impl_->file.reset();
    if (!impl_->tmp.empty()) detail::removeTemporary(impl_->tmp);
    throw;
  }
}

ResultWriter::~ResultWriter() {
  if (impl_->committed) return;
  impl_->file.reset();
  if (!impl_->tmp.empty()) detail::removeTemporary(impl_->tmp);
}

std::size_t ResultWriter::rows() const { return impl_->rows; }

std::size_t ResultWriter::appendOffset() const { return impl_->file ? impl_->file->appended() : 0; }

void ResultWriter::appendInPlace(float* rgb, std::size_t rows) {
  if (impl_->committed) throw std::logic_error("ResultWriter::appendInPlace after commit");
  if (!impl_->npy) return append(rgb, rows);
  impl_->file->appendInPlace(reinterpret_cast<char*>(rgb), rows * 3 * sizeof(float));
  impl_->rows += rows;
}

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
  if (impl_->npy && impl_->header) {
    const std::string h = npyHeader(impl_->rows);
    impl_->file->patch(0, h.data(), h.size());
  }
  impl_->file->close();
  impl_->file.reset();
  if (impl_->target.kind == detail::OutputKind::File) {
    detail::commitTemporary(impl_->tmp, impl_->target.path, impl_->path);
  } else if (!impl_->tmp.empty()) {
    const int fd = detail::openStream(impl_->target, impl_->path);
    try {
      detail::copyFile(impl_->tmp, fd, impl_->path);
    } catch (...) {
      if (impl_->target.kind == detail::OutputKind::Stream) ::close(fd);
      throw;
    }
    detail::closeStream(fd, impl_->target, impl_->path);
    detail::removeTemporary(impl_->tmp);
  }
  impl_->committed = true;
}

void writeResults(const std::string& path, const std::vector<float>& rgb) {
  if (rgb.size() % 3 != 0) throw std::invalid_argument("writeResults: rgb.size() is not a multiple of 3");
  ResultWriter w(path);
  w.append(rgb.data(), rgb.size() / 3);
  w.commit();
}

}  // namespace brdfcl
