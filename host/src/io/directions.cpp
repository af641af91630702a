// Direction normalization shared by every reader (brdfcl/io.hpp normalizeDirection and the
// block runs of io/directions.hpp). Built with -ffp-contract=off -fno-math-errno (CMakeLists.txt)
// so that the scalar and the vectorized loops round every operation the same way.
#include "io/directions.hpp"

#include <algorithm>
#include <cmath>

#include "brdfcl/io.hpp"

// The runs are compiled twice where the compiler can dispatch at load time: AVX2 doubles the
// width of the loops, and every clone rounds exactly as the baseline does.
#if defined(__GNUC__) && !defined(__clang__) && defined(__x86_64__) && !defined(__SANITIZE_ADDRESS__)
#define BRDFCL_CLONES __attribute__((target_clones("avx2", "default")))
#else
#define BRDFCL_CLONES
#endif

namespace brdfcl {

namespace {

// Rows are normalized in float: x / sqrt((x*x + y*y) + z*z), each operation rounded to float
// (within 3 ulp of the exact unit vector). A squared length in this range neither overflows nor
// loses more than 2^-50 of itself to subnormal squares; a row outside it is rescaled first.
constexpr float kLo = 0x1p-96f, kHi = 0x1p+96f;

inline float squaredLength(float x, float y, float z) { return (x * x + y * y) + z * z; }

// Compile-time strides let the compiler turn the interleaved loads into shuffles.
template <std::size_t Stride, class T, class Store>
inline std::size_t run(const T* src, std::size_t n, Store store) {
  std::size_t bad = 0;
  for (std::size_t i = 0; i < n; ++i) {
    const float x = static_cast<float>(src[i * Stride]), y = static_cast<float>(src[i * Stride + 1]),
                z = static_cast<float>(src[i * Stride + 2]);
    const float s = squaredLength(x, y, z);
    // Branch-free, so that the loop vectorizes: false for NaN and infinities too.
    const bool ok = (s >= kLo) & (s <= kHi);
    const float len = std::sqrt(ok ? s : 1.0f);
    store(i, x / len, y / len, z / len);
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

// The block runs' arithmetic, and for the rows they leave undone (a length beyond float's range
// after rounding each component to float) a rescaling by 2^-e in double first, which is exact:
// such a row gets the value the float formula gives its power-of-two multiple in range.
bool normalizeDirection(const double* d, float* dst) {
  float x = static_cast<float>(d[0]), y = static_cast<float>(d[1]), z = static_cast<float>(d[2]);
  float s = squaredLength(x, y, z);
  if (!((s >= kLo) & (s <= kHi))) {
    const double m = std::max({std::fabs(d[0]), std::fabs(d[1]), std::fabs(d[2])});
    if (!(m > 0.0)) return false;
    const int e = std::ilogb(m);
    x = static_cast<float>(std::scalbn(d[0], -e));
    y = static_cast<float>(std::scalbn(d[1], -e));
    z = static_cast<float>(std::scalbn(d[2], -e));
    s = squaredLength(x, y, z);
  }
  const float len = std::sqrt(s);
  dst[0] = x / len, dst[1] = y / len, dst[2] = z / len;
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
