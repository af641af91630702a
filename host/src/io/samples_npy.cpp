// Samples NPY (https://numpy.org/doc/stable/reference/generated/numpy.lib.format.html): the
// header dict, then each chunk of rows as one pread (C order) or one per column (Fortran order),
// checked on several threads.
#include "io/samples_npy.hpp"

#include <algorithm>
#include <cctype>
#include <charconv>
#include <cstdint>
#include <cstring>
#include <stdexcept>
#include <string_view>

#include "brdfcl/error.hpp"
#include "io/messages.hpp"
#include "io/rows.hpp"

static_assert(__BYTE_ORDER__ == __ORDER_LITTLE_ENDIAN__, "the NPY reader copies little-endian data as-is");

namespace brdfcl::detail::samples {
namespace {

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

}  // namespace

bool NpyReader::next(std::size_t maxRows, Samples& out) {
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

bool NpyReader::nextRows(std::size_t maxRows, SampleStream::RawRows& out) {
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

[[noreturn]] void NpyReader::throwRowError(const SampleStream::RawRows& rows, std::size_t i) const {
  Samples one;
  allocateSamples(1, true, one);
  const RowChecker checker(materialCount_, true, one);
  ChunkError error;
  readNpyRows<float>(reinterpret_cast<const char*>(rows.data.data() + 7 * i), 1, 0, 1, 7, false, checker, error);
  if (!error.message.empty()) throw Error(name_ + ": row " + std::to_string(rows.firstRow + i) + ": " + error.message);
  throw Error(name_ + ": row " + std::to_string(rows.firstRow + i) + ": internal: reported as bad by the device", 3);
}

void NpyReader::selectRows(std::size_t first, std::size_t count) {
  if (first > rows_ || count > rows_ - first) throw std::logic_error("SampleStream::selectRows: rows past the end");
  first_ = pos_ = first;
  end_ = first + count;
}

void NpyReader::read(std::size_t offset, char* dst, std::size_t n) const {
  if (src_.readAt(offset, dst, n) != n)  // the file shrank after the header was checked
    throw Error(name_ + ": truncated while reading (was the file changed during the run?)");
}

void NpyReader::readHeader(bool optional) {
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

}  // namespace brdfcl::detail::samples
