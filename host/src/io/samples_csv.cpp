// Samples CSV: the header (columns in any order, by name), then the rows a chunk of lines at a
// time; each chunk is parsed on several threads, without per-row allocation, and line numbers
// run on across chunks.
#include "io/samples_csv.hpp"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <stdexcept>
#include <string_view>

#include "brdfcl/error.hpp"
#include "io/input_limits.hpp"
#include "io/messages.hpp"
#include "io/rows.hpp"

namespace brdfcl::detail::samples {
namespace {

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

}  // namespace

bool CsvReader::next(std::size_t maxRows, Samples& out) {
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

void CsvReader::rewind() {
  offset_ = bodyOffset_;
  begin_ = end_ = 0;
  eof_ = false;
  line_ = rangeLine_;
  rows_ = 0;
  pendingBlank_ = 0;
}

// Lines after the header up to the last non-blank one, by parseCsvLines's rule for a blank
// line (spaces and tabs, and one '\r' before its end).
std::size_t CsvReader::countRows() const {
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

void CsvReader::selectRows(std::size_t first, std::size_t count) {
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

// `count` lines past buf_[begin_] come before the long one.
[[noreturn]] void CsvReader::throwLongLine(std::size_t count) const {
  throw Error(name_ + ": line " + std::to_string((headerRead_ ? line_ : 1) + count) + " is longer than " +
              detail::byteLimitText(detail::kMaxCsvLineBytes) +
              "; a samples line holds 6 or 7 numbers: check that this is the samples CSV file");
}

void CsvReader::readHeader(bool optional) {
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
bool CsvReader::restIsBlank(std::size_t from) const {
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
std::size_t CsvReader::fill(std::size_t lines) {
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
std::size_t CsvReader::parse(const char* p, const char* end, Samples& out) {
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

}  // namespace brdfcl::detail::samples
