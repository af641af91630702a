// Direction normalization shared by every reader (brdfcl/io.hpp normalizeDirection and the
// block runs of io/directions.hpp). Built with -ffp-contract=off -fno-math-errno (CMakeLists.txt)
// so that the scalar and the vectorized loops round every operation the same way.
#include "io/directions.hpp"

#include <algorithm>
#include <cmath>

#include "brdfcl/io.hpp"

// The runs are compiled twice where the compiler can dispatch at load time: AVX2 doubles the
// width of the double-precision loops, and every clone rounds exactly as the baseline does.
#if defined(__GNUC__) && !defined(__clang__) && defined(__x86_64__) && !defined(__SANITIZE_ADDRESS__)
#define BRDFCL_CLONES __attribute__((target_clones("avx2", "default")))
#else
#define BRDFCL_CLONES
#endif

namespace brdfcl {

namespace {

// Squared lengths in this range need no rescaling: 1/sqrt(s) and x/sqrt(s) neither overflow nor
// lose bits to subnormals. Every float32 row that is not zero lies in it (its squares are exact
// in double), so rescaling only ever happens for float64 input of extreme magnitude.
constexpr double kLo = 0x1p-1000, kHi = 0x1p+1000;

// x/|v|, rounded to float, as 1/sqrt(s) then a product: one division a row, not three.
inline void unit(double x, double y, double z, double s, float* ox, float* oy, float* oz) {
  const double r = 1.0 / std::sqrt(s);
  *ox = static_cast<float>(x * r);
  *oy = static_cast<float>(y * r);
  *oz = static_cast<float>(z * r);
}

inline double squaredLength(double x, double y, double z) { return (x * x + y * y) + z * z; }

// Compile-time strides let the compiler turn the interleaved loads into shuffles.
template <std::size_t Stride, class T, class Store>
inline std::size_t run(const T* src, std::size_t n, Store store) {
  std::size_t bad = 0;
  for (std::size_t i = 0; i < n; ++i) {
    const double x = src[i * Stride], y = src[i * Stride + 1], z = src[i * Stride + 2];
    const double s = squaredLength(x, y, z);
    // Branch-free, so that the loop vectorizes: false for NaN and infinities too.
    const bool ok = (s >= kLo) & (s <= kHi);
    const double r = 1.0 / std::sqrt(ok ? s : 1.0);
    store(i, static_cast<float>(x * r), static_cast<float>(y * r), static_cast<float>(z * r));
    bad += std::size_t(!ok);
  }
  return bad;
}

template <class T, class Store>
inline std::size_t dispatch(const T* src, std::size_t stride, std::size_t n, Store store) {
  switch (stride) {
    case 3: return run<3>(src, n, store);
    case 6: return run<6>(src, n, store);
    case 7: return run<7>(src, n, store);
    default: {
      std::size_t bad = 0;
      for (std::size_t i = 0; i < n; ++i) bad += run<0>(src + i * stride, 1, [&](std::size_t, float x, float y, float z) {
        store(i, x, y, z);
      });
      return bad;
    }
  }
}

template <std::size_t Stride, class T>
inline std::size_t indices(const T* src, std::size_t n, std::size_t count, std::uint32_t* dst) {
  // Indices below 2^31 and `count` convert exactly; anything else (negative, fractional, NaN,
  // huge) fails the round trip or the bound and is left to the per-row check.
  const T limit = static_cast<T>(std::min<std::size_t>(count, std::size_t(1) << 31));
  std::size_t bad = 0;
  for (std::size_t i = 0; i < n; ++i) {
    const T m = src[i * Stride];
    const bool inRange = (m >= T(0)) & (m < limit);
    const std::int32_t k = static_cast<std::int32_t>(inRange ? m : T(0));
    dst[i] = static_cast<std::uint32_t>(k);
    bad += std::size_t(!(inRange & (static_cast<T>(k) == m)));
  }
  return bad;
}

template <class T>
std::size_t indicesAnyStride(const T* src, std::size_t stride, std::size_t n, std::size_t count, std::uint32_t* dst) {
  switch (stride) {
    case 7: return indices<7>(src, n, count, dst);
    case 1: return indices<1>(src, n, count, dst);
    default: {
      std::size_t bad = 0;
      for (std::size_t i = 0; i < n; ++i) bad += indices<0>(src + i * stride, 1, count, dst + i);
      return bad;
    }
  }
}

}  // namespace

// The block runs' arithmetic, with rescaling by a power of two for the rare rows outside
// [kLo, kHi]: scaling by 2^-e is exact, so a rescaled row gets the value the plain formula
// would give if it could not overflow or underflow.
bool normalizeDirection(const double* d, float* dst) {
  double x = d[0], y = d[1], z = d[2];
  double s = squaredLength(x, y, z);
  if (!(s >= kLo && s <= kHi)) {
    const double m = std::max({std::fabs(x), std::fabs(y), std::fabs(z)});
    if (!(m > 0.0)) return false;
    const int e = std::ilogb(m);
    x = std::scalbn(x, -e), y = std::scalbn(y, -e), z = std::scalbn(z, -e);
    s = squaredLength(x, y, z);
  }
  unit(x, y, z, s, dst, dst + 1, dst + 2);
  return true;
}

namespace detail {

BRDFCL_CLONES std::size_t normalizeToPlanes(const float* src, std::size_t stride, std::size_t n, float* dx, float* dy,
                                            float* dz) {
  return dispatch(src, stride, n, [=](std::size_t i, float x, float y, float z) { dx[i] = x, dy[i] = y, dz[i] = z; });
}

BRDFCL_CLONES std::size_t normalizeToPlanes(const double* src, std::size_t stride, std::size_t n, float* dx,
                                            float* dy, float* dz) {
  return dispatch(src, stride, n, [=](std::size_t i, float x, float y, float z) { dx[i] = x, dy[i] = y, dz[i] = z; });
}

BRDFCL_CLONES std::size_t normalizeToRows(const float* src, std::size_t stride, std::size_t n, float* dst) {
  return dispatch(src, stride, n, [=](std::size_t i, float x, float y, float z) {
    dst[3 * i] = x, dst[3 * i + 1] = y, dst[3 * i + 2] = z;
  });
}

BRDFCL_CLONES std::size_t normalizeToRows(const double* src, std::size_t stride, std::size_t n, float* dst) {
  return dispatch(src, stride, n, [=](std::size_t i, float x, float y, float z) {
    dst[3 * i] = x, dst[3 * i + 1] = y, dst[3 * i + 2] = z;
  });
}

BRDFCL_CLONES std::size_t materialIndices(const float* src, std::size_t stride, std::size_t n, std::size_t count,
                                          std::uint32_t* dst) {
  return indicesAnyStride(src, stride, n, count, dst);
}

BRDFCL_CLONES std::size_t materialIndices(const double* src, std::size_t stride, std::size_t n, std::size_t count,
                                          std::uint32_t* dst) {
  return indicesAnyStride(src, stride, n, count, dst);
}

}  // namespace detail

}  // namespace brdfcl
