// The samples CSV reader: a header naming the columns in any order, then rows of 6 or 7 numbers,
// read a chunk of lines at a time (SampleStream) or whole (readSamples).
#pragma once
#include <algorithm>
#include <cstddef>
#include <limits>
#include <string>
#include <utility>
#include <vector>

#include "brdfcl/io.hpp"
#include "io/sample_source.hpp"

namespace brdfcl::detail::samples {

// The file's columns: a permutation fixed by the header, so rows in any column order cost one
// indexed store per field.
struct CsvLayout {
  int fields = 0;
  const char* names[7] = {};  // in the file's order
  int slot[7] = {};           // where field k goes among the RowChecker's values
  std::string header;         // the names, comma-separated, for messages
};

// CSV a chunk of lines at a time. The buffer holds the lines not yet parsed; each chunk is cut
// after a newline, so every line is parsed exactly once, and line numbers run on across chunks.
class CsvReader {
 public:
  CsvReader(const Source& src, std::string name, std::size_t materialCount, bool optional)
      : src_(src), name_(std::move(name)), materialCount_(materialCount) {
    readHeader(optional);
  }

  bool hasMaterial() const { return layout_.fields == 7; }

  bool next(std::size_t maxRows, Samples& out);
  void rewind();
  std::size_t countRows() const;
  // Finds the byte range of lines [first, first + count) after the header and reads only it.
  void selectRows(std::size_t first, std::size_t count);

 private:
  static constexpr std::size_t kBlock = std::size_t(4) << 20;

  std::size_t limit() const { return std::min(src_.size(), limit_); }

  [[noreturn]] void throwLongLine(std::size_t count) const;
  void readHeader(bool optional);
  bool restIsBlank(std::size_t from) const;
  std::size_t fill(std::size_t lines);
  std::size_t parse(const char* p, const char* end, Samples& out);

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

}  // namespace brdfcl::detail::samples
