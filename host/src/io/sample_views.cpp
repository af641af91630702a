// readSampleViews and writeTable (brdfcl/sampling_io.hpp): the whole file read at once (sampling
// runs produce far more rows than they read), checked row by row with the samples readers' words.
#include <cmath>
#include <cstdio>
#include <cstring>
#include <string>
#include <vector>

#include <fmt/format.h>

#include "brdfcl/error.hpp"
#include "brdfcl/io.hpp"
#include "brdfcl/sampling_io.hpp"
#include "io/messages.hpp"
#include "io/output.hpp"
#include "io/rows.hpp"
#include "io/sample_source.hpp"

namespace brdfcl {

namespace {

const char* const kNames[7] = {"material", "Vx", "Vy", "Vz", "u1", "u2", "u3"};

// Checks one row of values in kNames order (present[k] says whether column k exists) and stores
// it; returns the problem, without the file/line prefix.
std::string storeRow(const double* v, const bool* present, std::size_t materialCount, SampleViews& out) {
  for (int k = 0; k < 7; ++k)
    if (present[k] && !std::isfinite(v[k]))
      return fmt::format("field '{}' is not finite: {}", kNames[k], detail::formatNumber(v[k]));
  std::uint32_t index = 0;
  if (present[0]) {
    const double m = v[0];
    if (m < 0.0 || std::floor(m) != m) return "material index " + detail::formatNumber(m) + " is not a non-negative integer";
    if (m >= double(materialCount))
      return fmt::format("material index {} out of range ({} material{})", detail::formatNumber(m), materialCount,
                         materialCount == 1 ? "" : "s");
    index = std::uint32_t(m);
  }
  float d[3];
  if (!normalizeDirection(v + 1, d)) return "V has zero length";
  for (int k = 4; k < 7; ++k)
    if (present[k] && !(v[k] >= 0.0 && v[k] < 1.0 && float(v[k]) < 1.0f))
      return fmt::format("field '{}' must be in [0, 1), got {}", kNames[k], detail::formatNumber(v[k]));
  if (present[0]) out.material.push_back(index);
  out.V.insert(out.V.end(), d, d + 3);
  if (present[4])
    for (int k = 4; k < 7; ++k) out.u.push_back(float(v[k]));
  return {};
}

std::string readAll(const std::string& path) {
  detail::samples::Source src(path);
  std::string bytes(src.size(), '\0');
  bytes.resize(src.readAt(0, bytes.data(), bytes.size()));
  return bytes;
}

SampleViews readCsv(const std::string& text, const std::string& name, std::size_t materialCount) {
  std::size_t pos = 0, line = 1;
  auto nextLine = [&](std::string& out) {
    if (pos >= text.size()) return false;
    std::size_t end = text.find('\n', pos);
    if (end == std::string::npos) end = text.size();
    out.assign(text, pos, end - pos);
    if (!out.empty() && out.back() == '\r') out.pop_back();
    pos = end + 1;
    return true;
  };
  std::string header;
  if (!nextLine(header)) throw Error(name + ": empty file; expected a header such as material,Vx,Vy,Vz,u1,u2,u3");
  int slot[7];
  bool present[7] = {};
  int fields = 0;
  for (std::size_t b = 0;; ++fields) {
    std::size_t e = header.find(',', b);
    std::string col = header.substr(b, e == std::string::npos ? std::string::npos : e - b);
    while (!col.empty() && col.back() == ' ') col.pop_back();
    while (!col.empty() && col.front() == ' ') col.erase(0, 1);
    int k = 0;
    while (k < 7 && col != kNames[k]) ++k;
    if (k == 7) throw Error(fmt::format("{}: header: unknown column '{}'; expected material,Vx,Vy,Vz,u1,u2,u3",
                                        name, detail::printable(col)));
    if (present[k]) throw Error(fmt::format("{}: header: column {} appears twice", name, kNames[k]));
    present[k] = true;
    slot[fields] = k;
    if (fields == 6 || e == std::string::npos) {
      ++fields;
      if (e != std::string::npos) throw Error(name + ": header: more than 7 columns; expected material,Vx,Vy,Vz,u1,u2,u3");
      break;
    }
    b = e + 1;
  }
  for (int k = 1; k < 4; ++k)
    if (!present[k]) throw Error(fmt::format("{}: header: missing column {}", name, kNames[k]));
  if (present[4] + present[5] + present[6] != 0 && present[4] + present[5] + present[6] != 3)
    throw Error(name + ": header: give all of u1,u2,u3 or none");
  SampleViews out;
  std::string row;
  while (nextLine(row)) {
    ++line;
    if (row.find_first_not_of(" \t") == std::string::npos) continue;
    double v[7] = {};
    const char* p = row.c_str();
    for (int f = 0; f < fields; ++f) {
      char* end = nullptr;
      const double x = std::strtod(p, &end);
      const char* stop = end;
      while (*stop == ' ') ++stop;
      if (end == p || (*stop != ',' && *stop != '\0') || (*stop == '\0' && f + 1 < fields) || (*stop == ',' && f + 1 == fields))
        throw Error(fmt::format("{}:{}: expected {} numbers ({}), got '{}'", name, line, fields, header,
                                detail::printable(row)));
      v[slot[f]] = x;
      p = stop + 1;
    }
    const std::string problem = storeRow(v, present, materialCount, out);
    if (!problem.empty()) throw Error(fmt::format("{}:{}: {}", name, line, problem));
  }
  if (out.size() == 0) throw Error(name + ": no views");
  return out;
}

// NPY v1/v2/v3 of '<f4' or '<f8', C order, shape (N, C) with C one of 3, 4, 6, 7.
SampleViews readNpy(const std::string& bytes, const std::string& name, std::size_t materialCount) {
  auto bad = [&](const std::string& why) { return Error(name + ": " + why); };
  if (bytes.size() < 10 || bytes.compare(0, 6, "\x93NUMPY") != 0) throw bad("not an NPY file");
  const unsigned major = static_cast<unsigned char>(bytes[6]);
  std::size_t hlen = 0, start = 0;
  if (major == 1) {
    hlen = static_cast<unsigned char>(bytes[8]) | std::size_t(static_cast<unsigned char>(bytes[9])) << 8;
    start = 10;
  } else if (bytes.size() >= 12) {
    for (int k = 0; k < 4; ++k) hlen |= std::size_t(static_cast<unsigned char>(bytes[8 + k])) << (8 * k);
    start = 12;
  }
  if (start == 0 || hlen > bytes.size() - start) throw bad("truncated NPY header");
  const std::string h = bytes.substr(start, hlen);
  const bool f4 = h.find("'<f4'") != std::string::npos, f8 = h.find("'<f8'") != std::string::npos;
  if (!f4 && !f8) throw bad("dtype must be float32 or float64 (little-endian)");
  if (h.find("'fortran_order': False") == std::string::npos) throw bad("must be in C order");
  std::size_t rows = 0, cols = 0;
  const std::size_t s = h.find("'shape': (");
  if (s == std::string::npos || std::sscanf(h.c_str() + s + 10, "%zu, %zu)", &rows, &cols) != 2)
    throw bad("shape must be (N, 7), (N, 6), (N, 4) or (N, 3)");
  if (cols != 7 && cols != 6 && cols != 4 && cols != 3) throw bad(fmt::format("shape (N, {}): expected 7, 6, 4 or 3 columns", cols));
  const std::size_t item = f4 ? 4 : 8, data = start + hlen;
  if (rows == 0) throw bad("no views");
  if ((bytes.size() - data) / item / cols < rows) throw bad("file is shorter than its shape says");
  bool present[7] = {cols == 7 || cols == 4, true, true, true, cols >= 6, cols >= 6, cols >= 6};
  SampleViews out;
  for (std::size_t r = 0; r < rows; ++r) {
    double v[7] = {};
    int k = present[0] ? 0 : 1;
    for (std::size_t c = 0; c < cols; ++c, ++k) {
      const char* p = bytes.data() + data + (r * cols + c) * item;
      if (f4) {
        float x;
        std::memcpy(&x, p, 4);
        v[k] = x;
      } else {
        std::memcpy(&v[k], p, 8);
      }
    }
    const std::string problem = storeRow(v, present, materialCount, out);
    if (!problem.empty()) throw Error(fmt::format("{}: row {}: {}", name, r, problem));
  }
  return out;
}

}  // namespace

SampleViews readSampleViews(const std::string& path, std::size_t materialCount) {
  const std::string name = detail::samples::displayName(path);
  const std::string bytes = readAll(path);
  const bool npy = path == "-" ? bytes.compare(0, 6, "\x93NUMPY") == 0 : detail::hasNpyExtension(path);
  return npy ? readNpy(bytes, name, materialCount) : readCsv(bytes, name, materialCount);
}

void writeTable(const std::string& path, const std::vector<std::string>& columns, const std::vector<float>& values) {
  const std::size_t cols = columns.size(), rows = cols ? values.size() / cols : 0;
  const detail::OutputTarget target = detail::resolveOutput(path);
  const bool npy = detail::outputExtension(path, target) == ".npy";
  std::string out;
  if (npy) {
    out = detail::npyHeader(rows, cols);
    out.append(reinterpret_cast<const char*>(values.data()), values.size() * 4);
  } else {
    for (std::size_t c = 0; c < cols; ++c) out += (c ? "," : "") + columns[c];
    out += '\n';
    char buf[32];
    for (std::size_t r = 0; r < rows; ++r)
      for (std::size_t c = 0; c < cols; ++c) {
        const int n = std::snprintf(buf, sizeof buf, "%.9g", double(values[r * cols + c]));
        out.append(buf, std::size_t(n));
        out += c + 1 < cols ? ',' : '\n';
      }
  }
  writeOutput(path, out.data(), out.size());
}

}  // namespace brdfcl
