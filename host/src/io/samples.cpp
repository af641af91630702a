// Sample input (CSV or .npy: material, L, V per row) and result output (r,g,b as CSV or .npy),
// plus writeAtomically, which every output goes through so a failed run never leaves a partial file.
// Files may hold millions of rows: mapped input, parallel from_chars/to_chars, no per-row allocation.
#include <fcntl.h>
#include <sys/mman.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <cctype>
#include <cerrno>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <exception>
#include <filesystem>
#include <functional>
#include <stdexcept>
#include <string>
#include <string_view>
#include <system_error>
#include <thread>
#include <vector>

#include "io/messages.hpp"
#include "brdfcl/error.hpp"
#include "brdfcl/io.hpp"

static_assert(__BYTE_ORDER__ == __ORDER_LITTLE_ENDIAN__, "the NPY reader and writer copy little-endian data as-is");

namespace brdfcl {
namespace {

using detail::printable;
using detail::formatNumber;

constexpr const char* kColumns[7] = {"material", "Lx", "Ly", "Lz", "Vx", "Vy", "Vz"};
constexpr const char* kHeaderWithMaterial = "material,Lx,Ly,Lz,Vx,Vy,Vz";
constexpr const char* kHeaderWithoutMaterial = "Lx,Ly,Lz,Vx,Vy,Vz";

bool hasNpyExtension(const std::string& path) {
  if (path.size() < 4) return false;
  std::string ext = path.substr(path.size() - 4);
  std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return std::tolower(c); });
  return ext == ".npy";
}

// The whole input file. Large regular files are mapped rather than read: copying (and first
// zero-filling) a buffer of the file's size costs as much as parsing a third of it.
class InputFile {
 public:
  explicit InputFile(const std::string& path) {
    const int fd = ::open(path.c_str(), O_RDONLY | O_CLOEXEC);
    if (fd < 0) fail(path, errno);
    struct stat st {};
    if (::fstat(fd, &st) != 0 || S_ISDIR(st.st_mode)) {
      const int err = S_ISDIR(st.st_mode) ? EISDIR : errno;
      ::close(fd);
      fail(path, err);
    }
    if (S_ISREG(st.st_mode) && st.st_size >= (1 << 20)) {
      const std::size_t size = static_cast<std::size_t>(st.st_size);
      void* p = ::mmap(nullptr, size, PROT_READ, MAP_PRIVATE | MAP_POPULATE, fd, 0);
      if (p != MAP_FAILED) {
        ::close(fd);
        map_ = p;
        data_ = static_cast<const char*>(p);
        size_ = size;
        return;
      }
    }
    // Small files, pipes and /proc files (whose st_size is 0): read until EOF.
    buffer_.resize(S_ISREG(st.st_mode) && st.st_size > 0 ? static_cast<std::size_t>(st.st_size) + 1 : 65536);
    std::size_t used = 0;
    for (;;) {
      if (used == buffer_.size()) buffer_.resize(buffer_.size() * 2);
      const ssize_t n = ::read(fd, &buffer_[used], buffer_.size() - used);
      if (n < 0 && errno == EINTR) continue;
      if (n < 0) {
        const int err = errno;
        ::close(fd);
        fail(path, err);
      }
      if (n == 0) break;
      used += static_cast<std::size_t>(n);
    }
    ::close(fd);
    buffer_.resize(used);
    data_ = buffer_.data();
    size_ = used;
  }
  ~InputFile() {
    if (map_) ::munmap(map_, size_);
  }
  InputFile(const InputFile&) = delete;
  InputFile& operator=(const InputFile&) = delete;

  const char* data() const { return data_; }
  std::size_t size() const { return size_; }

 private:
  [[noreturn]] static void fail(const std::string& path, int err) {
    throw Error("cannot read samples file '" + printable(path, 300) + "': " + std::strerror(err));
  }

  void* map_ = nullptr;
  std::string buffer_;
  const char* data_ = nullptr;
  std::size_t size_ = 0;
};

// The checks every row gets, whatever the file format; rows are written in place so workers
// can fill disjoint parts of one Samples. Returns an empty string or the reason (without the
// file/line prefix, which the caller knows how to spell).
class RowChecker {
 public:
  RowChecker(std::size_t materialCount, bool hasMaterial, Samples& out)
      : materialCount_(materialCount), hasMaterial_(hasMaterial), out_(out) {}

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
  // Dividing by the largest component first keeps x*x+y*y+z*z from overflowing (1e200) or
  // underflowing (1e-200) in double: any finite non-zero vector normalizes.
  static bool normalize(const double* d, float* dst) {
    const double m = std::max({std::fabs(d[0]), std::fabs(d[1]), std::fabs(d[2])});
    if (!(m > 0.0)) return false;
    const double x = d[0] / m, y = d[1] / m, z = d[2] / m;
    const double len = std::sqrt(x * x + y * y + z * z);
    const float fx = static_cast<float>(x / len), fy = static_cast<float>(y / len), fz = static_cast<float>(z / len);
    if (!std::isfinite(fx) || !std::isfinite(fy) || !std::isfinite(fz)) return false;
    dst[0] = fx;
    dst[1] = fy;
    dst[2] = fz;
    return true;
  }

  static std::string direction(const char* which, const double* d) {
    if (d[0] == 0.0 && d[1] == 0.0 && d[2] == 0.0) return std::string(which) + " has zero length";
    return std::string(which) + " cannot be normalized";
  }

  std::size_t materialCount_;
  bool hasMaterial_;
  Samples& out_;
};

Samples allocateSamples(std::size_t rows, bool hasMaterial) {
  Samples s;
  if (hasMaterial) s.material.resize(rows);
  s.L.resize(3 * rows);
  s.V.resize(3 * rows);
  return s;
}

// ---------------------------------------------------------------------------------------------
// Parallel parsing and formatting: number conversion dominates, and rows are independent.

std::size_t workerCount(std::size_t bytes) {
  const std::size_t cores = std::max(1u, std::thread::hardware_concurrency());
  return std::min<std::size_t>({cores, 64, bytes / (1u << 20) + 1});  // >= 1 MiB per worker
}

// Runs body(0..n-1) concurrently, the calling thread taking part; rethrows the first exception.
void parallelFor(std::size_t n, const std::function<void(std::size_t)>& body) {
  std::vector<std::exception_ptr> errors(n);
  const auto run = [&](std::size_t i) {
    try {
      body(i);
    } catch (...) {
      errors[i] = std::current_exception();
    }
  };
  std::vector<std::thread> threads;
  std::size_t next = 1;
  for (; next < n; ++next) {
    try {
      threads.emplace_back(run, next);
    } catch (const std::system_error&) {
      break;  // no more threads available: the rest runs here
    }
  }
  if (n > 0) run(0);
  for (; next < n; ++next) run(next);
  for (auto& t : threads) t.join();
  for (auto& e : errors)
    if (e) std::rethrow_exception(e);
}

// The first problem one worker met in its share of the rows.
struct ChunkError {
  std::string message;  // without the "file:line: " prefix; empty if the chunk was fine
  std::size_t at = 0;   // line (CSV) or row (NPY), relative to the chunk
};

// ---------------------------------------------------------------------------------------------
// CSV

bool isBlank(char c) { return c == ' ' || c == '\t'; }

std::string_view trim(std::string_view s) {
  while (!s.empty() && isBlank(s.front())) s.remove_prefix(1);
  while (!s.empty() && isBlank(s.back())) s.remove_suffix(1);
  return s;
}

bool allBlank(const char* p, const char* end) {
  for (; p < end; ++p)
    if (!isBlank(*p) && *p != '\r' && *p != '\n') return false;
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
  return static_cast<const char*>(std::memchr(p, '\n', static_cast<std::size_t>(end - p)));
}

// Lines in [p, end), counting an unterminated last line.
std::size_t countLines(const char* p, const char* end) {
  const std::size_t n = static_cast<std::size_t>(std::count(p, end, '\n'));
  return n + (p < end && end[-1] != '\n' ? 1 : 0);
}

struct CsvLayout {
  int fields;
  const char* const* names;
  const char* header;
};

// Parses the lines in [p, end) into rows firstRow.. of the output. `fileEnd` tells trailing
// blank lines (ignored) from blank lines followed by more data (an error). Returns the rows parsed.
std::size_t parseCsvChunk(const char* p, const char* end, const char* fileEnd, const CsvLayout& layout,
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
      if (allBlank(p, fileEnd)) return line;
      return fail("empty line; expected " + std::to_string(layout.fields) + " fields (" + layout.header + ")");
    }
    if (!splitFields(text, fields, layout.fields))
      return fail("expected " + std::to_string(layout.fields) + " fields (" + layout.header + "), got " +
                  std::to_string(countFields(text)));
    for (int k = 0; k < layout.fields; ++k) {
      if (!parseDouble(fields[k], values[k]))
        return fail(std::string("field '") + layout.names[k] + "' is not a number: '" + printable(trim(fields[k])) +
                    "'");
      if (!std::isfinite(values[k]))
        return fail(std::string("field '") + layout.names[k] + "' is not finite: '" + printable(trim(fields[k])) + "'");
    }
    std::string problem = checker.set(firstRow + line, values);
    if (!problem.empty()) return fail(std::move(problem));
  }
  return line;
}

Samples readCsv(const char* begin, const char* const fileEnd, const std::string& name, std::size_t materialCount,
                bool optional) {
  if (fileEnd - begin >= 3 && std::memcmp(begin, "\xEF\xBB\xBF", 3) == 0) begin += 3;  // spreadsheets add a BOM

  const std::string expectedHeader = std::string("'") + kHeaderWithMaterial + "'" +
                                     (optional ? std::string(" or '") + kHeaderWithoutMaterial + "'" : "");
  if (allBlank(begin, fileEnd)) throw Error(name + ": empty file; expected the header " + expectedHeader);
  const char* nl = findNewline(begin, fileEnd);
  std::string_view line(begin, static_cast<std::size_t>((nl ? nl : fileEnd) - begin));
  if (!line.empty() && line.back() == '\r') line.remove_suffix(1);
  const char* const body = nl ? nl + 1 : fileEnd;

  // R's write.csv and some spreadsheets quote the column names, never the numbers.
  const auto nameIs = [](std::string_view field, const char* expected) {
    field = trim(field);
    if (field.size() >= 2 && field.front() == '"' && field.back() == '"') field = field.substr(1, field.size() - 2);
    return field == expected;
  };
  std::string_view header[7];
  bool hasMaterial = false;
  bool headerOk = false;
  if (splitFields(line, header, 7)) {
    headerOk = true;
    for (int k = 0; k < 7; ++k) headerOk = headerOk && nameIs(header[k], kColumns[k]);
    hasMaterial = true;
  } else if (optional && splitFields(line, header, 6)) {
    headerOk = true;
    for (int k = 0; k < 6; ++k) headerOk = headerOk && nameIs(header[k], kColumns[k + 1]);
  }
  if (!headerOk) {
    const std::size_t comma = line.find(',');
    double ignored;
    const bool looksLikeData =
        parseDouble(line.substr(0, comma == std::string_view::npos ? line.size() : comma), ignored);
    throw Error(name + ":1: " + (looksLikeData ? "missing header" : "bad header '" + printable(line) + "'") +
                "; the first line must be " + expectedHeader);
  }
  const CsvLayout layout{hasMaterial ? 7 : 6, hasMaterial ? kColumns : kColumns + 1,
                         hasMaterial ? kHeaderWithMaterial : kHeaderWithoutMaterial};

  // Chunks start after a '\n', so every line belongs to exactly one chunk.
  const std::size_t workers = workerCount(static_cast<std::size_t>(fileEnd - body));
  std::vector<const char*> bounds(workers + 1, fileEnd);
  bounds[0] = body;
  for (std::size_t w = 1; w < workers; ++w) {
    const char* guess = std::max(
        bounds[w - 1], body + (fileEnd - body) / static_cast<std::ptrdiff_t>(workers) * static_cast<std::ptrdiff_t>(w));
    const char* cut = findNewline(guess, fileEnd);
    bounds[w] = cut ? cut + 1 : fileEnd;
  }
  // Counting lines first lets every worker write straight into the one output.
  std::vector<std::size_t> firstRow(workers + 1, 0);
  parallelFor(workers, [&](std::size_t w) { firstRow[w + 1] = countLines(bounds[w], bounds[w + 1]); });
  for (std::size_t w = 0; w < workers; ++w) firstRow[w + 1] += firstRow[w];

  Samples out = allocateSamples(firstRow[workers], hasMaterial);
  const RowChecker checker(materialCount, hasMaterial, out);
  std::vector<ChunkError> errors(workers);
  std::vector<std::size_t> parsed(workers);
  parallelFor(workers, [&](std::size_t w) {
    parsed[w] = parseCsvChunk(bounds[w], bounds[w + 1], fileEnd, layout, checker, firstRow[w], errors[w]);
  });
  for (std::size_t w = 0; w < workers; ++w) {
    if (errors[w].message.empty()) continue;
    // Header is line 1; the body starts at line 2.
    throw Error(name + ":" + std::to_string(2 + firstRow[w] + errors[w].at) + ": " + errors[w].message);
  }
  // Only trailing blank lines are skipped, so the parsed rows form a prefix of the output.
  std::size_t rows = 0;
  for (std::size_t w = 0; w < workers && rows == firstRow[w]; ++w) rows += parsed[w];
  if (rows == 0) throw Error(name + ": no samples (the file has a header but no rows)");
  if (hasMaterial) out.material.resize(rows);
  out.L.resize(3 * rows);
  out.V.resize(3 * rows);
  return out;
}

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

Samples readNpy(const char* d, std::size_t size, const std::string& name, std::size_t materialCount, bool optional) {
  if (size < 10 || std::memcmp(d, "\x93NUMPY", 6) != 0)
    throw Error(name + ": not an NPY file (no \\x93NUMPY magic); save it with numpy.save");
  const unsigned major = static_cast<unsigned char>(d[6]), minor = static_cast<unsigned char>(d[7]);
  if (minor != 0 || major < 1 || major > 3)
    throw Error(name + ": unsupported NPY format version " + std::to_string(major) + "." + std::to_string(minor) +
                " (supported: 1.0, 2.0, 3.0)");
  // Version 1.0 has a 2-byte header length, 2.0 and 3.0 a 4-byte one (both little-endian).
  const std::size_t headerStart = major == 1 ? 10 : 12;
  if (size < headerStart) throw Error(name + ": truncated NPY header");
  std::size_t headerLength =
      static_cast<unsigned char>(d[8]) | static_cast<std::size_t>(static_cast<unsigned char>(d[9])) << 8;
  if (major > 1) {
    std::uint32_t len;
    std::memcpy(&len, d + 8, 4);
    headerLength = len;
  }
  if (headerLength > size - headerStart) throw Error(name + ": truncated NPY header");

  const NpyHeader h = NpyHeaderParser(std::string_view(d + headerStart, headerLength), name).parse();
  if (!h.haveDescr || !h.haveFortran || !h.haveShape)
    throw Error(name + ": malformed NPY header (needs 'descr', 'fortran_order' and 'shape'): " +
                printable(std::string_view(d + headerStart, headerLength), 120));
  if (h.structured)
    throw Error(name +
                ": structured dtypes are not supported; expected a plain float32 ('<f4') or float64 ('<f8') array");

  std::size_t itemSize = 0;
  if (h.descr.size() == 3 && h.descr[1] == 'f' && (h.descr[2] == '4' || h.descr[2] == '8')) {
    if (h.descr[0] == '>')
      throw Error(name + ": big-endian data ('" + h.descr + "') is not supported; convert with arr.astype('<f" +
                  h.descr[2] + "')");
    if (h.descr[0] == '<' || h.descr[0] == '|' || h.descr[0] == '=') itemSize = h.descr[2] == '4' ? 4 : 8;
  }
  if (itemSize == 0)
    throw Error(name + ": unsupported dtype '" + printable(h.descr) +
                "'; expected float32 ('<f4') or float64 ('<f8'), e.g. arr.astype('<f4')");

  const bool shapeOk = h.shape.size() == 2 && (h.shape[1] == 7 || (optional && h.shape[1] == 6));
  if (!shapeOk)
    throw Error(name + ": expected shape (N, 7) with columns " + kHeaderWithMaterial +
                (optional ? std::string(" or (N, 6) with columns ") + kHeaderWithoutMaterial : std::string()) +
                ", got " + shapeText(h.shape));
  const int cols = static_cast<int>(h.shape[1]);
  const std::uint64_t rows = h.shape[0];
  if (rows == 0) throw Error(name + ": no samples (shape " + shapeText(h.shape) + ")");

  const std::size_t dataStart = headerStart + headerLength;
  const std::size_t rowBytes = static_cast<std::size_t>(cols) * itemSize;
  const std::size_t rowsPresent = (size - dataStart) / rowBytes;
  if (rows > rowsPresent)  // compared before multiplying: a corrupt shape must not overflow
    throw Error(name + ": truncated: expected " + std::to_string(rows) + " rows of " + std::to_string(cols) +
                (itemSize == 4 ? " float32" : " float64") + ", file has " + std::to_string(rowsPresent));

  Samples out = allocateSamples(rows, cols == 7);
  const RowChecker checker(materialCount, cols == 7, out);
  const std::size_t workers = workerCount(rows * rowBytes);
  std::vector<ChunkError> errors(workers);
  parallelFor(workers, [&](std::size_t w) {
    const std::size_t first = rows * w / workers, last = rows * (w + 1) / workers;
    if (itemSize == 4)
      readNpyRows<float>(d + dataStart, rows, first, last, cols, h.fortranOrder, checker, errors[w]);
    else
      readNpyRows<double>(d + dataStart, rows, first, last, cols, h.fortranOrder, checker, errors[w]);
  });
  for (const auto& e : errors)  // rows are 0-based, as numpy indexes them
    if (!e.message.empty()) throw Error(name + ": row " + std::to_string(e.at) + ": " + e.message);
  return out;
}

// ---------------------------------------------------------------------------------------------
// Output

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

void writeNpy(OutputFile& f, const std::vector<float>& rgb) {
  std::string header =
      "{'descr': '<f4', 'fortran_order': False, 'shape': (" + std::to_string(rgb.size() / 3) + ", 3), }";
  // Magic (6) + version (2) + length (2) + header + '\n' must be a multiple of 64.
  const std::size_t total = (10 + header.size() + 1 + 63) / 64 * 64;
  header.append(total - 10 - header.size() - 1, ' ');
  header += '\n';
  const std::size_t len = header.size();
  const char prefix[10] = {
      '\x93', 'N', 'U', 'M', 'P', 'Y', 1, 0, static_cast<char>(len & 0xff), static_cast<char>(len >> 8)};
  f.append(prefix, sizeof prefix);
  f.append(header.data(), header.size());
  f.append(rgb.data(), rgb.size() * sizeof(float));
}

void writeCsv(OutputFile& f, const std::vector<float>& rgb) {
  f.append("r,g,b\n", 6);
  // Rounds of `batch` rows per worker: formatting runs in parallel, writing in file order, and
  // memory stays bounded whatever the row count.
  constexpr std::size_t batch = 1 << 16;
  constexpr std::size_t maxValue = 24;  // "%.9g" of a float needs at most 15 characters
  const std::size_t rows = rgb.size() / 3;
  const std::size_t workers = workerCount(rows * 3 * 12);
  std::vector<std::vector<char>> text(workers, std::vector<char>(batch * 3 * maxValue));
  std::vector<std::size_t> used(workers);
  for (std::size_t start = 0; start < rows; start += workers * batch) {
    parallelFor(workers, [&](std::size_t w) {
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

std::atomic<unsigned> tmpCounter{0};

}  // namespace

Samples readSamples(const std::string& path, std::size_t materialCount, bool materialColumnOptional) {
  const InputFile file(path);
  const std::string name = printable(path, 300);
  if (hasNpyExtension(path)) return readNpy(file.data(), file.size(), name, materialCount, materialColumnOptional);
  return readCsv(file.data(), file.data() + file.size(), name, materialCount, materialColumnOptional);
}

void writeResults(const std::string& path, const std::vector<float>& rgb) {
  if (rgb.size() % 3 != 0) throw std::invalid_argument("writeResults: rgb.size() is not a multiple of 3");
  const bool npy = hasNpyExtension(path);
  writeAtomically(path, [&](const std::string& tmpPath) {
    OutputFile f(tmpPath, path);
    if (npy)
      writeNpy(f, rgb);
    else
      writeCsv(f, rgb);
    f.close();
  });
}

void writeAtomically(const std::string& path, const std::function<void(const std::string& tmpPath)>& write) {
  namespace fs = std::filesystem;
  const std::string shown = printable(path, 300);
  const fs::path target(path);
  const std::string fileName = target.filename().string();
  if (fileName.empty() || fileName == "." || fileName == "..")
    throw Error("cannot write '" + shown + "': not a file name");
  // Fail before the (possibly long) write rather than at the rename.
  struct stat st {};
  if (::stat(path.c_str(), &st) == 0 && S_ISDIR(st.st_mode))
    throw Error("cannot write '" + shown + "': " + std::strerror(EISDIR));

  // Same directory, so rename() is atomic; dot-prefixed so directory listings ignore it.
  const fs::path dir = target.parent_path();
  const std::string stem = "." + fileName.substr(0, 200) + ".tmp." + std::to_string(::getpid()) + ".";
  std::string tmp;
  for (int attempt = 0;; ++attempt) {
    tmp = (dir / (stem + std::to_string(tmpCounter.fetch_add(1)))).string();
    // O_EXCL: a stale temporary of a crashed run with the same pid must not be reused.
    const int fd = ::open(tmp.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, 0666);
    if (fd >= 0) {
      ::close(fd);
      break;
    }
    if (errno != EEXIST || attempt > 100) throw Error("cannot write '" + shown + "': " + std::strerror(errno));
  }
  try {
    write(tmp);
    if (std::rename(tmp.c_str(), path.c_str()) != 0)
      throw Error("cannot write '" + shown + "': " + std::strerror(errno));
  } catch (...) {
    ::unlink(tmp.c_str());
    throw;
  }
}

}  // namespace brdfcl
