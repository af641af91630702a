// Pieces every samples reader shares: the file's bytes (Source: pread on demand, or a pipe read
// whole), the per-row checks (RowChecker), the output sizing and a worker's first error.
#pragma once
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <string>

#include "brdfcl/io.hpp"
#include "io/directions.hpp"
#include "io/messages.hpp"

namespace brdfcl::detail::samples {

inline constexpr const char* kColumns[7] = {"material", "Lx", "Ly", "Lz", "Vx", "Vy", "Vz"};
inline constexpr const char* kHeaderWithMaterial = "material,Lx,Ly,Lz,Vx,Vy,Vz";
inline constexpr const char* kHeaderWithoutMaterial = "Lx,Ly,Lz,Vx,Vy,Vz";
inline constexpr const char* kGridHint = "pass --grid to evaluate every material at each direction pair";

// "-" is stdin, in every message too.
std::string displayName(const std::string& path);

// The bytes of the samples file. A regular file is read on demand with pread, so memory stays
// bounded by what the caller asks for; pipes and /proc files (st_size 0, no seeking) are read
// whole at once, up to maxJsonBytes(): the readers rewind and count rows, which a stream cannot
// do, and a stream that never ends (/dev/zero) must not take all memory first.
class Source {
 public:
  explicit Source(const std::string& path);
  ~Source() { release(); }
  Source(const Source&) = delete;
  Source& operator=(const Source&) = delete;

  std::size_t size() const { return size_; }

  // Copies up to n bytes from `offset`; fewer only at the end of the file.
  std::size_t readAt(std::size_t offset, char* dst, std::size_t n) const;

 private:
  [[noreturn]] void fail(int err) const;
  void release();

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
inline void allocateSamples(std::size_t rows, bool hasMaterial, Samples& out) {
  out.material.resize(hasMaterial ? rows : 0);
  out.L.resize(3 * rows);
  out.V.resize(3 * rows);
}

inline void shrinkSamples(std::size_t rows, Samples& out) {
  if (!out.material.empty()) out.material.resize(rows);
  out.L.resize(3 * rows);
  out.V.resize(3 * rows);
}

// The first problem one worker met in its share of the rows.
struct ChunkError {
  std::string message;  // without the "file:line: " prefix; empty if the chunk was fine
  std::size_t at = 0;   // line (CSV) or row (NPY), relative to the worker's share
};

}  // namespace brdfcl::detail::samples
