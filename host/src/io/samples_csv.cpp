// Sample input: CSV (columns in any order, by header name) or .npy rows of material, L, V, from a
// file or stdin ("-"), read whole (readSamples) or a chunk at a time (SampleStream) with the same
// checks and messages. Regular files are read with pread into one
// reusable buffer, never mapped; each chunk is parsed on several threads, without per-row allocation.
#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <limits>
#include <memory>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

#include "brdfcl/error.hpp"
#include "brdfcl/io.hpp"
#include "io/directions.hpp"
#include "io/input_limits.hpp"
#include "io/messages.hpp"
#include "io/rows.hpp"

static_assert(__BYTE_ORDER__ == __ORDER_LITTLE_ENDIAN__, "the NPY reader copies little-endian data as-is");

namespace brdfcl {
namespace {

using detail::formatNumber;
using detail::parallelFor;
using detail::printable;
using detail::workerCount;

constexpr const char* kColumns[7] = {"material", "Lx", "Ly", "Lz", "Vx", "Vy", "Vz"};
constexpr const char* kHeaderWithMaterial = "material,Lx,Ly,Lz,Vx,Vy,Vz";
constexpr const char* kHeaderWithoutMaterial = "Lx,Ly,Lz,Vx,Vy,Vz";
constexpr const char* kGridHint = "pass --grid to evaluate every material at each direction pair";

// "-" is stdin, in every message too.
std::string displayName(const std::string& path) { return path == "-" ? "<stdin>" : printable(path, 300); }

// The bytes of the samples file. A regular file is read on demand with pread, so memory stays
// bounded by what the caller asks for; pipes and /proc files (st_size 0, no seeking) are read
// whole at once, up to maxJsonBytes(): the readers rewind and count rows, which a stream cannot
// do, and a stream that never ends (/dev/zero) must not take all memory first.
class Source {
 public:
  explicit Source(const std::string& path) : name_(displayName(path)) {
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
  ~Source() { release(); }
  Source(const Source&) = delete;
  Source& operator=(const Source&) = delete;

  std::size_t size() const { return size_; }

  // Copies up to n bytes from `offset`; fewer only at the end of the file.
  std::size_t readAt(std::size_t offset, char* dst, std::size_t n) const {
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

 private:
  [[noreturn]] void fail(int err) const {
    throw Error("cannot read samples file '" + name_ + "': " + std::strerror(err));
  }

  void release() {
    if (fd_ >= 0 && ownsFd_) ::close(fd_);
    fd_ = -1;
  }

  std::string name_;
  int fd_ = -1;
  bool ownsFd_ = true;
  std::string whole_;
  std::size_t size_ = 0;
};

// The checks every row gets, whatever the file format; rows are written in place so workers
// can fill disjoint parts of one Samples. Returns an empty string or the reason (without the
// file/line prefix, which the caller knows how to spell).
class RowChecker {
 public:
  RowChecker(std::size_t materialCount, bool hasMaterial, Samples& out)
      : materialCount_(materialCount), hasMaterial_(hasMaterial), out_(out) {}

  // Rows [row, row + n) of a C-order float32 or float64 array with `cols` columns from `src`:
  // the vectorized runs of io/directions.hpp, the same bits as set(). Returns false when some
  // row is left undone (a problem, or an extreme vector); the caller then goes row by row.
  template <typename T>
  bool setBlock(std::size_t row, std::size_t n, const T* src, int cols) const {
    std::size_t undone = 0;
    if (hasMaterial_) {
      undone += detail::materialIndices(src, std::size_t(cols), n, materialCount_ ? materialCount_ : SIZE_MAX,
                                        &out_.material[row]);
      ++src;
    }
    undone += detail::normalizeToRows(src, std::size_t(cols), n, &out_.L[3 * row]);
    undone += detail::normalizeToRows(src + 3, std::size_t(cols), n, &out_.V[3 * row]);
    return undone == 0;
  }

  // v holds 7 values (material first) or 6 when the file has no material column.
  std::string set(std::size_t row, const double* v) const {
    const char* const* names = hasMaterial_ ? kColumns : kColumns + 1;
    const int n = hasMaterial_ ? 7 : 6;
    for (int k = 0; k < n; ++k)
      if (!std::isfinite(v[k])) return std::string("field '") + names[k] + "' is not finite: " + formatNumber(v[k]);
    if (hasMaterial_) {
      const double m = v[0];
      if (m < 0.0 || std::floor(m) != m) return "material index " + formatNumber(m) + " is not a non-negative integer";
      if (materialCount_ != 0 && m >= static_cast<double>(materialCount_))
        return "material index " + formatNumber(m) + " out of range (" + std::to_string(materialCount_) +
               (materialCount_ == 1 ? " material)" : " materials)");
      if (m > 4294967295.0) return "material index " + formatNumber(m) + " is too large";
      out_.material[row] = static_cast<std::uint32_t>(m);
      ++v;
    }
    if (!normalize(v, &out_.L[3 * row])) return direction("L", v);
    if (!normalize(v + 3, &out_.V[3 * row])) return direction("V", v + 3);
    return {};
  }

 private:
  static bool normalize(const double* d, float* dst) { return normalizeDirection(d, dst); }

  static std::string direction(const char* which, const double*) { return std::string(which) + " has zero length"; }

  std::size_t materialCount_;
  bool hasMaterial_;
  Samples& out_;
};

// Sizes `out` for `rows` rows; vectors keep their capacity, so a stream's chunks reuse memory.
void allocateSamples(std::size_t rows, bool hasMaterial, Samples& out) {
  out.material.resize(hasMaterial ? rows : 0);
  out.L.resize(3 * rows);
  out.V.resize(3 * rows);
}

void shrinkSamples(std::size_t rows, Samples& out) {
  if (!out.material.empty()) out.material.resize(rows);
  out.L.resize(3 * rows);
  out.V.resize(3 * rows);
}

// The first problem one worker met in its share of the rows.
struct ChunkError {
  std::string message;  // without the "file:line: " prefix; empty if the chunk was fine
  std::size_t at = 0;   // line (CSV) or row (NPY), relative to the worker's share
};

// ---------------------------------------------------------------------------------------------
// CSV

bool isBlank(char c) { return c == ' ' || c == '\t'; }

std::string_view trim(std::string_view s) {
  while (!s.empty() && isBlank(s.front())) s.remove_prefix(1);
  while (!s.empty() && isBlank(s.back())) s.remove_suffix(1);
  return s;
}

// Whether [p, end) holds only blank lines, by the rule a line is held to (one '\r' before its
// '\n' is dropped, then spaces and tabs): a '\r' anywhere else makes its line non-blank. The
// readers ask both questions, so the two must agree or a file's first error depends on chunking.
bool allBlank(const char* p, const char* end) {
  for (; p < end; ++p) {
    if (isBlank(*p) || *p == '\n') continue;
    if (*p == '\r' && (p + 1 == end || p[1] == '\n')) continue;
    return false;
  }
  return true;
}

// Full-consumption parse; accepts what strtod accepts in practice (leading '+', inf, nan) so the
// finiteness check can say "not finite" instead of "not a number".
bool parseDouble(std::string_view s, double& out) {
  s = trim(s);
  if (!s.empty() && s.front() == '+') {
    s.remove_prefix(1);
    if (s.empty() || s.front() == '+' || s.front() == '-') return false;
  }
  if (s.empty()) return false;
  const auto r = std::from_chars(s.data(), s.data() + s.size(), out);
  if (r.ptr != s.data() + s.size()) return false;
  if (r.ec == std::errc::result_out_of_range) {
    // from_chars leaves `out` alone on overflow and underflow; strtod gives inf or the nearest
    // (sub)normal, which is what a user writing 1e-400 means.
    const std::string copy(s);
    out = std::strtod(copy.c_str(), nullptr);
    return true;
  }
  return r.ec == std::errc();
}

// Splits a line into exactly `n` fields without allocating; false if the count differs.
bool splitFields(std::string_view line, std::string_view* fields, int n) {
  std::size_t pos = 0;
  for (int k = 0; k < n; ++k) {
    const std::size_t comma = line.find(',', pos);
    const bool last = (k == n - 1);
    if (last != (comma == std::string_view::npos)) return false;
    fields[k] = line.substr(pos, last ? std::string_view::npos : comma - pos);
    pos = comma + 1;
  }
  return true;
}

std::size_t countFields(std::string_view line) {
  if (trim(line).empty()) return 0;
  return 1 + static_cast<std::size_t>(std::count(line.begin(), line.end(), ','));
}

const char* findNewline(const char* p, const char* end) {
  if (p >= end) return nullptr;  // memchr must not see the null data() of an empty buffer
  return static_cast<const char*>(std::memchr(p, '\n', static_cast<std::size_t>(end - p)));
}

// Lines in [p, end), counting an unterminated last line.
std::size_t countLines(const char* p, const char* end) {
  const std::size_t n = static_cast<std::size_t>(std::count(p, end, '\n'));
  return n + (p < end && end[-1] != '\n' ? 1 : 0);
}

// The file's columns: a permutation fixed by the header, so rows in any column order cost one
// indexed store per field.
struct CsvLayout {
  int fields = 0;
  const char* names[7] = {};  // in the file's order
  int slot[7] = {};           // where field k goes among the RowChecker's values
  std::string header;         // the names, comma-separated, for messages
};

std::string emptyLineMessage(const CsvLayout& layout) {
  return "empty line; expected " + std::to_string(layout.fields) + " fields (" + layout.header + ")";
}

// Parses the lines in [p, end) into rows firstRow.. of the output. A blank line is fine only if
// nothing but blank lines follows it up to `chunkEnd`; the stream decides about the lines after
// the chunk. Returns the rows parsed (the lines before any trailing blank ones).
std::size_t parseCsvLines(const char* p, const char* end, const char* chunkEnd, const CsvLayout& layout,
                          const RowChecker& checker, std::size_t firstRow, ChunkError& error) {
  std::string_view fields[7];
  double values[7];
  std::size_t line = 0;
  const auto fail = [&](std::string message) {
    error.message = std::move(message);
    error.at = line;
    return line;
  };
  for (; p < end; ++line) {
    const char* nl = findNewline(p, end);
    std::string_view text(p, static_cast<std::size_t>((nl ? nl : end) - p));
    p = nl ? nl + 1 : end;
    if (!text.empty() && text.back() == '\r') text.remove_suffix(1);
    if (trim(text).empty()) {
      if (allBlank(p, chunkEnd)) return line;
      return fail(emptyLineMessage(layout));
    }
    if (!splitFields(text, fields, layout.fields))
      return fail("expected " + std::to_string(layout.fields) + " fields (" + layout.header + "), got " +
                  std::to_string(countFields(text)));
    for (int k = 0; k < layout.fields; ++k) {
      double& value = values[layout.slot[k]];
      if (!parseDouble(fields[k], value))
        return fail(std::string("field '") + layout.names[k] + "' is not a number: '" + printable(trim(fields[k])) +
                    "'");
      if (!std::isfinite(value))
        return fail(std::string("field '") + layout.names[k] + "' is not finite: '" + printable(trim(fields[k])) + "'");
    }
    std::string problem = checker.set(firstRow + line, values);
    if (!problem.empty()) return fail(std::move(problem));
  }
  return line;
}

// CSV a chunk of lines at a time. The buffer holds the lines not yet parsed; each chunk is cut
// after a newline, so every line is parsed exactly once, and line numbers run on across chunks.
class CsvReader {
 public:
  CsvReader(const Source& src, std::string name, std::size_t materialCount, bool optional)
      : src_(src), name_(std::move(name)), materialCount_(materialCount) {
    readHeader(optional);
  }

  bool hasMaterial() const { return layout_.fields == 7; }

  bool next(std::size_t maxRows, Samples& out) {
    for (;;) {
      const std::size_t cut = fill(maxRows);
      if (cut == begin_) {
        if (ranged_ && rows_ < rangeCount_)  // a blank run that the rows of a later range follow
          throw Error(name_ + ":" + std::to_string(rangeLine_ + rows_) + ": " + emptyLineMessage(layout_));
        if (rows_ == 0) throw Error(name_ + ": no samples (the file has a header but no rows)");
        shrinkSamples(0, out);
        return false;
      }
      const std::size_t rows = parse(buf_.data() + begin_, buf_.data() + cut, out);
      begin_ = cut;
      if (rows > 0) return true;
    }
  }

  void rewind() {
    offset_ = bodyOffset_;
    begin_ = end_ = 0;
    eof_ = false;
    line_ = rangeLine_;
    rows_ = 0;
    pendingBlank_ = 0;
  }

  // Lines after the header up to the last non-blank one, by parseCsvLines's rule for a blank
  // line (spaces and tabs, and one '\r' before its end).
  std::size_t countRows() const {
    std::vector<char> block(kBlock);
    std::size_t lines = 0, rows = 0;
    bool nonBlank = false, cr = false, any = false;
    for (std::size_t at = bodyOffset_;;) {
      const std::size_t n = src_.readAt(at, block.data(), block.size());
      if (n == 0) break;
      for (std::size_t i = 0; i < n; ++i) {
        const char c = block[i];
        if (cr && c != '\n') nonBlank = true;
        cr = false;
        any = true;
        if (c == '\n') {
          ++lines;
          if (nonBlank) rows = lines;
          nonBlank = any = false;
        } else if (c == '\r') {
          cr = true;
        } else if (!isBlank(c)) {
          nonBlank = true;
        }
      }
      at += n;
    }
    if (any && nonBlank) rows = lines + 1;
    return rows;
  }

  // Finds the byte range of lines [first, first + count) after the header and reads only it.
  void selectRows(std::size_t first, std::size_t count) {
    std::vector<char> block(kBlock);
    std::size_t lines = 0, start = first == 0 ? bodyOffset_ : std::string::npos, stop = src_.size();
    for (std::size_t at = bodyOffset_; lines < first + count;) {
      const std::size_t n = src_.readAt(at, block.data(), block.size());
      if (n == 0) break;
      for (const char* p = block.data(); (p = findNewline(p, block.data() + n)) != nullptr; ++p) {
        ++lines;
        const std::size_t after = at + static_cast<std::size_t>(p - block.data()) + 1;
        if (lines == first) start = after;
        if (lines == first + count) {
          stop = after;
          break;
        }
      }
      at += n;
    }
    if (start == std::string::npos) throw std::logic_error("SampleStream::selectRows: rows past the end");
    bodyOffset_ = start;
    limit_ = stop;
    ranged_ = true;
    rangeCount_ = count;
    rangeLine_ = 2 + first;
    rewind();
  }

 private:
  static constexpr std::size_t kBlock = std::size_t(4) << 20;

  std::size_t limit() const { return std::min(src_.size(), limit_); }

  // `count` lines past buf_[begin_] come before the long one.
  [[noreturn]] void throwLongLine(std::size_t count) const {
    throw Error(name_ + ": line " + std::to_string((headerRead_ ? line_ : 1) + count) + " is longer than " +
                detail::byteLimitText(detail::kMaxCsvLineBytes) +
                "; a samples line holds 6 or 7 numbers: check that this is the samples CSV file");
  }

  void readHeader(bool optional) {
    const std::string expectedHeader = std::string("'") + kHeaderWithMaterial + "'" +
                                       (optional ? std::string(" or '") + kHeaderWithoutMaterial + "'" : "");
    std::size_t cut = fill(1);
    if (end_ - begin_ >= 3 && std::memcmp(buf_.data() + begin_, "\xEF\xBB\xBF", 3) == 0)
      begin_ += 3;  // spreadsheets add a BOM
    const char* first = buf_.data() + begin_;
    if (allBlank(first, buf_.data() + cut) && restIsBlank(cut))
      throw Error(name_ + ": empty file; expected the header " + expectedHeader);
    std::string_view line(first, cut - begin_);
    if (!line.empty() && line.back() == '\n') line.remove_suffix(1);
    if (!line.empty() && line.back() == '\r') line.remove_suffix(1);

    const std::size_t firstComma = line.find(',');
    double ignored;
    if (parseDouble(line.substr(0, firstComma == std::string_view::npos ? line.size() : firstComma), ignored))
      throw Error(name_ + ":1: missing header; the first line must be " + expectedHeader);

    // Columns are found by name, so any order works; the permutation is fixed here, once.
    // R's write.csv and some spreadsheets quote the column names, never the numbers.
    int column[7] = {-1, -1, -1, -1, -1, -1, -1};  // canonical column -> field
    std::size_t pos = 0;
    for (int k = 0;; ++k) {
      const std::size_t comma = line.find(',', pos);
      std::string_view field = trim(line.substr(pos, comma == std::string_view::npos ? std::string_view::npos : comma - pos));
      if (field.size() >= 2 && field.front() == '"' && field.back() == '"') field = field.substr(1, field.size() - 2);
      const auto known = std::find(std::begin(kColumns), std::end(kColumns), field);
      if (known == std::end(kColumns)) {
        const std::string near = detail::closestName(field, std::vector<std::string_view>(std::begin(kColumns), std::end(kColumns)));
        throw Error(name_ + ": header: unknown column '" + printable(field) + "' (column " + std::to_string(k + 1) +
                    ")" + (near.empty() ? "; " : "; did you mean " + near + "? ") + "the columns are " +
                    kHeaderWithMaterial + " in any order");
      }
      const int c = static_cast<int>(known - std::begin(kColumns));
      if (column[c] >= 0)
        throw Error(name_ + ": header: column '" + kColumns[c] + "' appears twice (columns " +
                    std::to_string(column[c] + 1) + " and " + std::to_string(k + 1) + ")");
      column[c] = k;
      if (comma == std::string_view::npos) break;
      pos = comma + 1;
    }
    std::string missing;
    int missingCount = 0;
    for (int c = optional ? 1 : 0; c < 7; ++c)
      if (column[c] < 0) {
        missing += (missing.empty() ? "" : ", ") + std::string(kColumns[c]);
        ++missingCount;
      }
    if (missingCount > 0)
      throw Error(name_ + ": header: missing column" + (missingCount > 1 ? "s " : " ") + missing +
                  (column[0] < 0 ? std::string("; add it, or ") + kGridHint : std::string()));
    const bool hasMaterial = column[0] >= 0;
    layout_.fields = hasMaterial ? 7 : 6;
    for (int c = hasMaterial ? 0 : 1; c < 7; ++c) {
      const int k = column[c];
      layout_.names[k] = kColumns[c];
      layout_.slot[k] = hasMaterial ? c : c - 1;
    }
    for (int k = 0; k < layout_.fields; ++k) layout_.header += (k ? "," : "") + std::string(layout_.names[k]);
    begin_ = cut;
    bodyOffset_ = offset_ - (end_ - begin_);
    headerRead_ = true;
  }

  // Whether the file holds only blanks after buffer position `from` (reads ahead in blocks
  // without keeping them).
  bool restIsBlank(std::size_t from) const {
    if (!allBlank(buf_.data() + from, buf_.data() + end_)) return false;
    // A '\r' ending one piece is blank only if the next piece starts with '\n'.
    bool endsInCr = end_ > from && buf_[end_ - 1] == '\r';
    std::vector<char> block(kBlock);
    for (std::size_t at = offset_;;) {
      const std::size_t n = src_.readAt(at, block.data(), block.size());
      if (n == 0) return true;
      if ((endsInCr && block[0] != '\n') || !allBlank(block.data(), block.data() + n)) return false;
      endsInCr = block[n - 1] == '\r';
      at += n;
    }
  }

  // Reads until the buffer holds `lines` complete lines past begin_ or the file ends; returns
  // the buffer position just after the last of them (end_ at the end of the file, which
  // includes an unterminated last line).
  std::size_t fill(std::size_t lines) {
    std::size_t count = 0, scan = begin_;
    for (;;) {
      while (count < lines) {
        const char* nl = findNewline(buf_.data() + scan, buf_.data() + end_);
        if (!nl) break;
        const std::size_t next = static_cast<std::size_t>(nl - buf_.data()) + 1;
        if (next - scan > detail::kMaxCsvLineBytes + 1) throwLongLine(count);
        scan = next;
        ++count;
      }
      if (count == lines) return scan;
      // Before the buffer grows further: a file without newlines (or the wrong file) would
      // otherwise be read whole into one line.
      if (end_ - scan > detail::kMaxCsvLineBytes) throwLongLine(count);
      if (eof_) return end_;
      // Keep the unparsed tail at the front, then read another block after it.
      if (begin_ > 0) {
        std::memmove(buf_.data(), buf_.data() + begin_, end_ - begin_);
        scan -= begin_;
        end_ -= begin_;
        begin_ = 0;
      }
      std::size_t want = kBlock;
      if (limit() >= offset_) {
        // +1 sees the end of the file in the same read. A whole-file read (readSamples) sizes
        // the buffer once instead of doubling it; a small file does not get a whole block.
        const std::size_t rest = limit() - offset_ + 1;
        want = lines == std::numeric_limits<std::size_t>::max() ? rest : std::min(kBlock, rest);
      }
      if (buf_.size() < end_ + want) buf_.resize(std::max(end_ + want, 2 * buf_.size()));
      std::size_t room = buf_.size() - end_;
      if (ranged_) room = std::min(room, limit_ > offset_ ? limit_ - offset_ : 0);
      const std::size_t n = room == 0 ? 0 : src_.readAt(offset_, buf_.data() + end_, room);
      if (n == 0) eof_ = true;
      offset_ += n;
      end_ += n;
    }
  }

  // Parses the complete lines in [p, end) into `out`; returns the rows (trailing blank lines
  // are not rows). A blank run that reaches the end of the chunk is remembered: it is an error
  // only if a later chunk holds data, as in the file read whole.
  std::size_t parse(const char* p, const char* end, Samples& out) {
    if (pendingBlank_ != 0 && !allBlank(p, end))
      throw Error(name_ + ":" + std::to_string(pendingBlank_) + ": " + emptyLineMessage(layout_));
    const std::size_t workers = workerCount(static_cast<std::size_t>(end - p));
    std::vector<const char*> bounds(workers + 1, end);
    bounds[0] = p;
    for (std::size_t w = 1; w < workers; ++w) {
      const char* guess =
          std::max(bounds[w - 1], p + (end - p) / static_cast<std::ptrdiff_t>(workers) * static_cast<std::ptrdiff_t>(w));
      const char* cut = findNewline(guess, end);
      bounds[w] = cut ? cut + 1 : end;
    }
    // Counting lines first lets every worker write straight into the one output.
    std::vector<std::size_t> firstRow(workers + 1, 0);
    parallelFor(workers, [&](std::size_t w) { firstRow[w + 1] = countLines(bounds[w], bounds[w + 1]); });
    for (std::size_t w = 0; w < workers; ++w) firstRow[w + 1] += firstRow[w];
    const std::size_t lines = firstRow[workers];

    allocateSamples(lines, hasMaterial(), out);
    const RowChecker checker(materialCount_, hasMaterial(), out);
    std::vector<ChunkError> errors(workers);
    std::vector<std::size_t> parsed(workers);
    parallelFor(workers, [&](std::size_t w) {
      parsed[w] = parseCsvLines(bounds[w], bounds[w + 1], end, layout_, checker, firstRow[w], errors[w]);
    });
    for (std::size_t w = 0; w < workers; ++w)
      if (!errors[w].message.empty())
        throw Error(name_ + ":" + std::to_string(line_ + firstRow[w] + errors[w].at) + ": " + errors[w].message);
    // Only trailing blank lines are skipped, so the parsed rows form a prefix of the output.
    std::size_t rows = 0;
    for (std::size_t w = 0; w < workers && rows == firstRow[w]; ++w) rows += parsed[w];
    if (rows < lines && pendingBlank_ == 0) pendingBlank_ = line_ + rows;
    shrinkSamples(rows, out);
    line_ += lines;
    rows_ += rows;
    return rows;
  }

  const Source& src_;
  std::string name_;
  std::size_t materialCount_;
  CsvLayout layout_{};
  std::vector<char> buf_;
  std::size_t begin_ = 0, end_ = 0;  // unparsed bytes in buf_
  std::size_t offset_ = 0;           // file offset of buf_[end_]
  std::size_t bodyOffset_ = 0;       // file offset of the first line after the header
  bool eof_ = false;
  bool headerRead_ = false;
  std::size_t line_ = 2;             // 1-based file line of buf_[begin_]; the header is line 1
  std::size_t rows_ = 0;             // rows returned so far
  std::size_t pendingBlank_ = 0;     // first line of a blank run that ended the last chunk
  // selectRows: the byte after the last line of the range, its rows and its first line.
  std::size_t limit_ = std::numeric_limits<std::size_t>::max();
  bool ranged_ = false;
  std::size_t rangeCount_ = 0, rangeLine_ = 2;
};

// ---------------------------------------------------------------------------------------------
// NPY (https://numpy.org/doc/stable/reference/generated/numpy.lib.format.html)

struct NpyHeader {
  std::string descr;
  bool fortranOrder = false;
  std::vector<std::uint64_t> shape;
  bool haveDescr = false, haveFortran = false, haveShape = false;
  bool structured = false;
};

// The header is a Python dict literal; this reads the subset numpy writes (strings, True/False,
// tuples of ints, Python 2's 123L) and skips values of keys it does not know.
class NpyHeaderParser {
 public:
  NpyHeaderParser(std::string_view text, const std::string& name) : s_(text), name_(name) {}

  NpyHeader parse() {
    NpyHeader h;
    expect('{');
    for (;;) {
      ws();
      if (peek() == '}') break;
      const std::string key = str();
      ws();
      expect(':');
      ws();
      if (key == "descr") {
        if (peek() == '[') {
          h.structured = true;
          skipValue();
        } else {
          h.descr = str();
        }
        h.haveDescr = true;
      } else if (key == "fortran_order") {
        const std::string_view word = identifier();
        if (word != "True" && word != "False") fail("fortran_order must be True or False");
        h.fortranOrder = word == "True";
        h.haveFortran = true;
      } else if (key == "shape") {
        h.shape = tuple();
        h.haveShape = true;
      } else {
        skipValue();
      }
      ws();
      if (peek() == ',') {
        ++i_;
        continue;
      }
      expect('}');
      return h;
    }
    ++i_;
    return h;
  }

 private:
  [[noreturn]] void fail(const std::string& why) const {
    throw Error(name_ + ": malformed NPY header (" + why + "): " + printable(s_, 120));
  }
  char peek() const { return i_ < s_.size() ? s_[i_] : '\0'; }
  void ws() {
    while (i_ < s_.size() && (s_[i_] == ' ' || s_[i_] == '\t' || s_[i_] == '\n' || s_[i_] == '\r')) ++i_;
  }
  void expect(char c) {
    ws();
    if (peek() != c) fail(std::string("expected '") + c + "'");
    ++i_;
  }
  std::string str() {
    const char q = peek();
    if (q != '\'' && q != '"') fail("expected a quoted string");
    const std::size_t end = s_.find(q, i_ + 1);
    if (end == std::string_view::npos) fail("unterminated string");
    std::string out(s_.substr(i_ + 1, end - i_ - 1));
    i_ = end + 1;
    return out;
  }
  std::string_view identifier() {
    const std::size_t start = i_;
    while (i_ < s_.size() && std::isalnum(static_cast<unsigned char>(s_[i_]))) ++i_;
    return s_.substr(start, i_ - start);
  }
  std::vector<std::uint64_t> tuple() {
    std::vector<std::uint64_t> dims;
    expect('(');
    for (;;) {
      ws();
      if (peek() == ')') break;
      std::uint64_t d = 0;
      const auto r = std::from_chars(s_.data() + i_, s_.data() + s_.size(), d);
      if (r.ec != std::errc()) fail("shape must be a tuple of non-negative integers");
      i_ = static_cast<std::size_t>(r.ptr - s_.data());
      if (peek() == 'L') ++i_;
      dims.push_back(d);
      ws();
      if (peek() == ',') {
        ++i_;
        continue;
      }
      if (peek() != ')') fail("expected ',' or ')' in shape");
    }
    ++i_;
    return dims;
  }
  void skipValue() {
    int depth = 0;
    while (i_ < s_.size()) {
      const char c = s_[i_];
      if (c == '\'' || c == '"') {
        str();
        continue;
      }
      if (c == '(' || c == '[' || c == '{') ++depth;
      if (c == ')' || c == ']' || c == '}') {
        if (depth == 0) return;
        --depth;
      }
      if (c == ',' && depth == 0) return;
      ++i_;
    }
  }

  std::string_view s_;
  const std::string& name_;
  std::size_t i_ = 0;
};

std::string shapeText(const std::vector<std::uint64_t>& shape) {
  std::string s = "(";
  for (std::size_t k = 0; k < shape.size(); ++k) s += (k ? ", " : "") + std::to_string(shape[k]);
  return s + (shape.size() == 1 ? ",)" : ")");
}

template <typename T>
void readNpyRows(const char* data, std::size_t rows, std::size_t first, std::size_t last, int cols, bool fortran,
                 const RowChecker& checker, ChunkError& error) {
  // C order (what numpy.save writes): whole blocks through the vectorized runs; a block with a
  // bad or extreme row is redone row by row below, which words the problem.
  constexpr std::size_t kBlock = 4096;
  if (!fortran) {
    const T* base = reinterpret_cast<const T*>(data);  // raw_ is malloc-aligned and rows are whole items
    for (; first < last; first += kBlock) {
      const std::size_t n = std::min(kBlock, last - first);
      if (!checker.setBlock(first, n, base + first * std::size_t(cols), cols)) break;
    }
    if (first >= last) return;
  }
  double values[7];
  for (std::size_t i = first; i < last; ++i) {
    for (int j = 0; j < cols; ++j) {
      const std::size_t idx = fortran ? static_cast<std::size_t>(j) * rows + i : i * static_cast<std::size_t>(cols) + j;
      T v;
      std::memcpy(&v, data + idx * sizeof(T), sizeof(T));  // data is not necessarily aligned
      values[j] = static_cast<double>(v);
    }
    std::string problem = checker.set(i, values);
    if (!problem.empty()) {
      error.message = std::move(problem);
      error.at = i;
      return;
    }
  }
}

// NPY rows a chunk at a time: the header is checked up front against the file size, then each
// chunk is one pread (C order) or one per column (Fortran order) into a reused buffer.
class NpyReader {
 public:
  NpyReader(const Source& src, std::string name, std::size_t materialCount, bool optional)
      : src_(src), name_(std::move(name)), materialCount_(materialCount) {
    readHeader(optional);
  }

  bool hasMaterial() const { return cols_ == 7; }

  bool next(std::size_t maxRows, Samples& out) {
    if (pos_ == end_) {
      shrinkSamples(0, out);
      return false;
    }
    const std::size_t count = std::min<std::size_t>(maxRows, end_ - pos_);
    raw_.resize(count * rowBytes());
    if (fortran_) {
      for (int j = 0; j < cols_; ++j)
        read(dataStart_ + (static_cast<std::size_t>(j) * rows_ + pos_) * itemSize_,
             raw_.data() + static_cast<std::size_t>(j) * count * itemSize_, count * itemSize_);
    } else {
      read(dataStart_ + pos_ * rowBytes(), raw_.data(), count * rowBytes());
    }
    allocateSamples(count, hasMaterial(), out);
    const RowChecker checker(materialCount_, hasMaterial(), out);
    const std::size_t workers = workerCount(count * rowBytes());
    std::vector<ChunkError> errors(workers);
    parallelFor(workers, [&](std::size_t w) {
      const std::size_t first = count * w / workers, last = count * (w + 1) / workers;
      if (itemSize_ == 4)
        readNpyRows<float>(raw_.data(), count, first, last, cols_, fortran_, checker, errors[w]);
      else
        readNpyRows<double>(raw_.data(), count, first, last, cols_, fortran_, checker, errors[w]);
    });
    for (const auto& e : errors)  // rows are 0-based, as numpy indexes them
      if (!e.message.empty()) throw Error(name_ + ": row " + std::to_string(pos_ + e.at) + ": " + e.message);
    pos_ += count;
    return true;
  }

  void rewind() { pos_ = first_; }

  bool hasRawRows() const { return itemSize_ == 4 && !fortran_ && hasMaterial() && materialCount_ > 0; }

  bool nextRows(std::size_t maxRows, SampleStream::RawRows& out) {
    out.count = 0;
    if (pos_ == end_) return false;
    const std::size_t count = std::min<std::size_t>(maxRows, end_ - pos_);
    out.data.resize(7 * count);
    read(dataStart_ + pos_ * rowBytes(), reinterpret_cast<char*>(out.data.data()), count * rowBytes());
    out.count = count;
    out.firstRow = pos_;
    pos_ += count;
    return true;
  }

  // The row through the readers' own checks, which word its problem.
  [[noreturn]] void throwRowError(const SampleStream::RawRows& rows, std::size_t i) const {
    Samples one;
    allocateSamples(1, true, one);
    const RowChecker checker(materialCount_, true, one);
    ChunkError error;
    readNpyRows<float>(reinterpret_cast<const char*>(rows.data.data() + 7 * i), 1, 0, 1, 7, false, checker, error);
    if (!error.message.empty()) throw Error(name_ + ": row " + std::to_string(rows.firstRow + i) + ": " + error.message);
    throw Error(name_ + ": row " + std::to_string(rows.firstRow + i) + ": internal: reported as bad by the device", 3);
  }

  std::size_t countRows() const { return rows_; }

  void selectRows(std::size_t first, std::size_t count) {
    if (first > rows_ || count > rows_ - first) throw std::logic_error("SampleStream::selectRows: rows past the end");
    first_ = pos_ = first;
    end_ = first + count;
  }

 private:
  std::size_t rowBytes() const { return static_cast<std::size_t>(cols_) * itemSize_; }

  void read(std::size_t offset, char* dst, std::size_t n) const {
    if (src_.readAt(offset, dst, n) != n)  // the file shrank after the header was checked
      throw Error(name_ + ": truncated while reading (was the file changed during the run?)");
  }

  void readHeader(bool optional) {
    const std::size_t size = src_.size();
    char prefix[12] = {};
    const std::size_t got = src_.readAt(0, prefix, sizeof prefix);
    if (got < 10 || std::memcmp(prefix, "\x93NUMPY", 6) != 0)
      throw Error(name_ + ": not an NPY file (no \\x93NUMPY magic); save it with numpy.save");
    const unsigned major = static_cast<unsigned char>(prefix[6]), minor = static_cast<unsigned char>(prefix[7]);
    if (minor != 0 || major < 1 || major > 3)
      throw Error(name_ + ": unsupported NPY format version " + std::to_string(major) + "." + std::to_string(minor) +
                  " (supported: 1.0, 2.0, 3.0)");
    // Version 1.0 has a 2-byte header length, 2.0 and 3.0 a 4-byte one (both little-endian).
    const std::size_t headerStart = major == 1 ? 10 : 12;
    if (got < headerStart) throw Error(name_ + ": truncated NPY header");
    std::size_t headerLength =
        static_cast<unsigned char>(prefix[8]) | static_cast<std::size_t>(static_cast<unsigned char>(prefix[9])) << 8;
    if (major > 1) {
      std::uint32_t len;
      std::memcpy(&len, prefix + 8, 4);
      headerLength = len;
    }
    if (headerLength > size - headerStart) throw Error(name_ + ": truncated NPY header");
    std::string text(headerLength, '\0');
    read(headerStart, text.data(), headerLength);

    const NpyHeader h = NpyHeaderParser(text, name_).parse();
    if (!h.haveDescr || !h.haveFortran || !h.haveShape)
      throw Error(name_ + ": malformed NPY header (needs 'descr', 'fortran_order' and 'shape'): " + printable(text, 120));
    if (h.structured)
      throw Error(name_ +
                  ": structured dtypes are not supported; expected a plain float32 ('<f4') or float64 ('<f8') array");

    if (h.descr.size() == 3 && h.descr[1] == 'f' && (h.descr[2] == '4' || h.descr[2] == '8')) {
      if (h.descr[0] == '>')
        throw Error(name_ + ": big-endian data ('" + h.descr + "') is not supported; convert with arr.astype('<f" +
                    h.descr[2] + "')");
      if (h.descr[0] == '<' || h.descr[0] == '|' || h.descr[0] == '=') itemSize_ = h.descr[2] == '4' ? 4 : 8;
    }
    if (itemSize_ == 0)
      throw Error(name_ + ": unsupported dtype '" + printable(h.descr) +
                  "'; expected float32 ('<f4') or float64 ('<f8'), e.g. arr.astype('<f4')");

    const bool shapeOk = h.shape.size() == 2 && (h.shape[1] == 7 || (optional && h.shape[1] == 6));
    if (!shapeOk)
      throw Error(name_ + ": expected shape (N, 7) with columns " + kHeaderWithMaterial +
                  (optional ? std::string(" or (N, 6) with columns ") + kHeaderWithoutMaterial : std::string()) +
                  ", got " + shapeText(h.shape) +
                  (!optional && h.shape.size() == 2 && h.shape[1] == 6
                       ? std::string("; without the material column, ") + kGridHint
                       : std::string()));
    cols_ = static_cast<int>(h.shape[1]);
    fortran_ = h.fortranOrder;
    if (h.shape[0] == 0) throw Error(name_ + ": no samples (shape " + shapeText(h.shape) + ")");

    dataStart_ = headerStart + headerLength;
    const std::size_t rowsPresent = (size - dataStart_) / rowBytes();
    if (h.shape[0] > rowsPresent)  // compared before multiplying: a corrupt shape must not overflow
      throw Error(name_ + ": truncated: expected " + std::to_string(h.shape[0]) + " rows of " + std::to_string(cols_) +
                  (itemSize_ == 4 ? " float32" : " float64") + ", file has " + std::to_string(rowsPresent) +
                  " complete rows");
    rows_ = end_ = static_cast<std::size_t>(h.shape[0]);
  }

  const Source& src_;
  std::string name_;
  std::size_t materialCount_;
  int cols_ = 0;
  std::size_t itemSize_ = 0;
  bool fortran_ = false;
  std::size_t dataStart_ = 0, rows_ = 0, pos_ = 0;
  std::size_t first_ = 0, end_ = 0;  // the rows next() returns (selectRows)
  std::vector<char> raw_;
};

}  // namespace

struct SampleStream::Impl {
  Source source;
  std::unique_ptr<CsvReader> csv;
  std::unique_ptr<NpyReader> npy;
  explicit Impl(const std::string& path) : source(path) {}
};

SampleStream::SampleStream(const std::string& path, std::size_t materialCount, bool materialColumnOptional)
    : impl_([&] {
        // A pipe is read whole here: an out-of-memory names the file.
        const detail::ReadingInput reading(displayName(path));
        return std::make_unique<Impl>(path);
      }()) {
  const std::string name = displayName(path);
  const detail::ReadingInput reading(name);
  // stdin has no extension: NPY's magic tells it from CSV (whose header cannot start with 0x93).
  char magic[6] = {};
  const bool npy = path == "-" ? impl_->source.readAt(0, magic, sizeof magic) == sizeof magic &&
                                     std::memcmp(magic, "\x93NUMPY", 6) == 0
                               : detail::hasNpyExtension(path);
  if (npy)
    impl_->npy = std::make_unique<NpyReader>(impl_->source, name, materialCount, materialColumnOptional);
  else
    impl_->csv = std::make_unique<CsvReader>(impl_->source, name, materialCount, materialColumnOptional);
}

SampleStream::~SampleStream() = default;

bool SampleStream::hasMaterialColumn() const { return impl_->npy ? impl_->npy->hasMaterial() : impl_->csv->hasMaterial(); }

bool SampleStream::next(std::size_t maxRows, Samples& out) {
  if (maxRows == 0) throw std::invalid_argument("SampleStream::next: maxRows must be at least 1");
  return impl_->npy ? impl_->npy->next(maxRows, out) : impl_->csv->next(maxRows, out);
}

void SampleStream::rewind() {
  if (impl_->npy)
    impl_->npy->rewind();
  else
    impl_->csv->rewind();
}

bool SampleStream::hasRawRows() const { return impl_->npy && impl_->npy->hasRawRows(); }

bool SampleStream::nextRows(std::size_t maxRows, RawRows& out) {
  if (maxRows == 0) throw std::invalid_argument("SampleStream::nextRows: maxRows must be at least 1");
  if (!hasRawRows()) throw std::logic_error("SampleStream::nextRows: this file's rows are not served raw");
  return impl_->npy->nextRows(maxRows, out);
}

void SampleStream::throwRowError(const RawRows& rows, std::size_t i) const {
  if (!hasRawRows() || i >= rows.count) throw std::logic_error("SampleStream::throwRowError: no such raw row");
  impl_->npy->throwRowError(rows, i);
}

std::size_t SampleStream::countRows() { return impl_->npy ? impl_->npy->countRows() : impl_->csv->countRows(); }

void SampleStream::selectRows(std::size_t first, std::size_t count) {
  if (count == 0) throw std::invalid_argument("SampleStream::selectRows: count must be at least 1");
  if (impl_->npy)
    impl_->npy->selectRows(first, count);
  else
    impl_->csv->selectRows(first, count);
}

Samples readSamples(const std::string& path, std::size_t materialCount, bool materialColumnOptional) {
  SampleStream stream(path, materialCount, materialColumnOptional);
  Samples out;
  stream.next(std::numeric_limits<std::size_t>::max(), out);
  return out;
}

}  // namespace brdfcl
