// SampleStream and readSamples: open the samples file (or stdin), tell NPY from CSV (by extension,
// or by NPY's magic on stdin) and hand each request to that format's reader.
#include <cstring>
#include <future>
#include <system_error>
#include <limits>
#include <memory>
#include <stdexcept>
#include <string>

#include "brdfcl/io.hpp"
#include "io/input_limits.hpp"
#include "io/rows.hpp"
#include "io/sample_source.hpp"
#include "io/samples_csv.hpp"
#include "io/samples_npy.hpp"

namespace brdfcl {

using detail::samples::CsvReader;
using detail::samples::displayName;
using detail::samples::NpyReader;
using detail::samples::Source;

struct SampleStream::Impl {
  Source source;
  std::unique_ptr<CsvReader> csv;
  std::unique_ptr<NpyReader> npy;
  // readAhead's chunk: read on its own thread from row aheadFrom, at most aheadMax rows. Last, so
  // that it is destroyed first: the future's destructor waits for the read, which uses npy.
  RawRows aheadRows;
  std::size_t aheadMax = 0, aheadFrom = 0;
  std::future<bool> ahead;
  explicit Impl(const std::string& path) : source(path) {}

  // Drops a chunk read ahead that the caller did not ask for, and goes back to where it began.
  void settle() {
    if (!ahead.valid()) return;
    try {
      ahead.get();
    } catch (...) {  // the read is done again, and fails again, when asked for
    }
    aheadRows = RawRows{};
    npy->seek(aheadFrom);
  }
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
  impl_->settle();
  return impl_->npy ? impl_->npy->next(maxRows, out) : impl_->csv->next(maxRows, out);
}

void SampleStream::rewind() {
  impl_->settle();
  if (impl_->npy)
    impl_->npy->rewind();
  else
    impl_->csv->rewind();
}

bool SampleStream::hasRawRows() const { return impl_->npy && impl_->npy->hasRawRows(); }

bool SampleStream::nextRows(std::size_t maxRows, RawRows& out) {
  if (maxRows == 0) throw std::invalid_argument("SampleStream::nextRows: maxRows must be at least 1");
  if (!hasRawRows()) throw std::logic_error("SampleStream::nextRows: this file's rows are not served raw");
  Impl& s = *impl_;
  if (s.ahead.valid() && maxRows == s.aheadMax) {
    const bool more = s.ahead.get();  // the read's error, if any, is this call's
    std::swap(out, s.aheadRows);
    s.aheadRows = RawRows{};
    return more;
  }
  s.settle();
  return s.npy->nextRows(maxRows, out);
}

void SampleStream::readAhead(std::size_t maxRows) {
  if (maxRows == 0 || !hasRawRows()) return;
  Impl& s = *impl_;
  s.settle();
  s.aheadFrom = s.npy->position();
  s.aheadMax = maxRows;
  try {
    s.ahead = std::async(std::launch::async, [&s, maxRows] { return s.npy->nextRows(maxRows, s.aheadRows); });
  } catch (const std::system_error&) {  // no thread to spare: nextRows reads it then
  }
}

void SampleStream::throwRowError(const RawRows& rows, std::size_t i) const {
  if (!hasRawRows() || i >= rows.count) throw std::logic_error("SampleStream::throwRowError: no such raw row");
  impl_->npy->throwRowError(rows, i);
}

std::size_t SampleStream::countRows() { return impl_->npy ? impl_->npy->countRows() : impl_->csv->countRows(); }

void SampleStream::selectRows(std::size_t first, std::size_t count) {
  if (count == 0) throw std::invalid_argument("SampleStream::selectRows: count must be at least 1");
  impl_->settle();
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
