// The samples NPY reader: a float32 or float64 array of shape (N, 7) or (N, 6), C or Fortran
// order, checked against the file size up front and read a chunk of rows at a time.
#pragma once
#include <cstddef>
#include <string>
#include <utility>
#include <vector>

#include "brdfcl/io.hpp"
#include "io/sample_source.hpp"

namespace brdfcl::detail::samples {

// NPY rows a chunk at a time: the header is checked up front against the file size, then each
// chunk is one pread (C order) or one per column (Fortran order) into a reused buffer.
class NpyReader {
 public:
  NpyReader(const Source& src, std::string name, std::size_t materialCount, bool optional)
      : src_(src), name_(std::move(name)), materialCount_(materialCount) {
    readHeader(optional);
  }

  bool hasMaterial() const { return cols_ == 7; }
  bool next(std::size_t maxRows, Samples& out);

  void rewind() { pos_ = first_; }
  std::size_t position() const { return pos_; }
  void seek(std::size_t row) { pos_ = row; }

  bool hasRawRows() const { return itemSize_ == 4 && !fortran_ && hasMaterial() && materialCount_ > 0; }

  bool nextRows(std::size_t maxRows, SampleStream::RawRows& out);

  // The row through the readers' own checks, which word its problem.
  [[noreturn]] void throwRowError(const SampleStream::RawRows& rows, std::size_t i) const;

  std::size_t countRows() const { return rows_; }

  void selectRows(std::size_t first, std::size_t count);

 private:
  std::size_t rowBytes() const { return static_cast<std::size_t>(cols_) * itemSize_; }

  void read(std::size_t offset, char* dst, std::size_t n) const;
  void readHeader(bool optional);

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

}  // namespace brdfcl::detail::samples
