// Direction normalization (host/src/io/directions.cpp): the vectorized block runs give the bits
// of the per-row normalizeDirection, both are within 3 ulp of a long-double reference, and
// rescaled extreme vectors equal their unscaled selves.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <random>
#include <vector>

#include "brdfcl/io.hpp"
#include "io/directions.hpp"

namespace {

using brdfcl::normalizeDirection;
namespace detail = brdfcl::detail;

// Directions of every length scale a float can hold, and some that only a double can.
std::vector<double> randomRows(std::size_t n, int minExp, int maxExp, std::uint64_t seed) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  std::uniform_int_distribution<int> e(minExp, maxExp);
  std::vector<double> rows(3 * n);
  for (std::size_t i = 0; i < n; ++i) {
    const int scale = e(rng);
    for (int c = 0; c < 3; ++c) rows[3 * i + c] = std::ldexp(u(rng), scale);
    if (i % 97 == 5) rows[3 * i + 1] = 0.0;  // axis-aligned and in-plane rows
    if (i % 89 == 3) rows[3 * i] = rows[3 * i + 1] = 0.0;
  }
  return rows;
}

bool sameBits(float a, float b) { return std::memcmp(&a, &b, sizeof a) == 0; }

TEST(Directions, Float32RunsEqualPerRow) {
  const std::size_t n = 20000;
  const auto d = randomRows(n, -40, 40, 1);
  std::vector<float> f(d.begin(), d.end());
  std::vector<float> x(n), y(n), z(n), rows(3 * n);
  ASSERT_EQ(detail::normalizeToPlanes(f.data(), 3, n, x.data(), y.data(), z.data()), 0u);
  ASSERT_EQ(detail::normalizeToRows(f.data(), 3, n, rows.data()), 0u);
  for (std::size_t i = 0; i < n; ++i) {
    const double row[3] = {f[3 * i], f[3 * i + 1], f[3 * i + 2]};
    float ref[3];
    ASSERT_TRUE(normalizeDirection(row, ref));
    const float got[3] = {x[i], y[i], z[i]};
    for (int c = 0; c < 3; ++c) {
      ASSERT_TRUE(sameBits(got[c], ref[c])) << "row " << i << " component " << c << ": plane " << got[c]
                                            << " vs per-row " << ref[c];
      ASSERT_TRUE(sameBits(rows[3 * i + c], ref[c])) << "row " << i << " component " << c;
    }
  }
}

TEST(Directions, Float64RunsEqualPerRowAndLeaveExtremesUndone) {
  const std::size_t n = 20000;
  const auto d = randomRows(n, -700, 700, 2);  // many rows need rescaling
  std::vector<float> x(n), y(n), z(n);
  const std::size_t undone = detail::normalizeToPlanes(d.data(), 3, n, x.data(), y.data(), z.data());
  std::size_t extreme = 0;
  for (std::size_t i = 0; i < n; ++i) {
    const double* row = &d[3 * i];
    const float f[3] = {float(row[0]), float(row[1]), float(row[2])};
    const float s = (f[0] * f[0] + f[1] * f[1]) + f[2] * f[2];
    const bool plain = s >= 0x1p-96f && s <= 0x1p+96f;
    extreme += !plain;
    float ref[3];
    ASSERT_TRUE(normalizeDirection(row, ref)) << "row " << i;
    const float got[3] = {x[i], y[i], z[i]};
    if (plain)
      for (int c = 0; c < 3; ++c) ASSERT_TRUE(sameBits(got[c], ref[c])) << "row " << i << " component " << c;
  }
  EXPECT_GT(extreme, n / 2);
  EXPECT_EQ(undone, extreme);
  // float32 rows beyond 2^48 in length are left to the per-row rescaling too.
  const float big[6] = {0x1p60f, 0, 1, 0, 0x1p-60f, 0};
  EXPECT_EQ(detail::normalizeToRows(big, 3, 2, x.data()), 2u);
}

// The stride-7 rows of an NPY file (material first), and an odd stride through the generic path.
TEST(Directions, StridedRowsAndIndices) {
  const std::size_t n = 3000;
  const auto d = randomRows(2 * n, -20, 20, 3);
  for (int stride : {7, 9}) {
    std::vector<float> file(stride * n);
    for (std::size_t i = 0; i < n; ++i) {
      file[stride * i] = float(i % 5);
      for (int c = 0; c < 6; ++c) file[stride * i + 1 + c] = float(d[6 * i + c]);
    }
    std::vector<float> L(3 * n);
    std::vector<std::uint32_t> index(n);
    ASSERT_EQ(detail::normalizeToRows(file.data() + 1, std::size_t(stride), n, L.data()), 0u);
    ASSERT_EQ(detail::materialIndices(file.data(), std::size_t(stride), n, 5, index.data()), 0u);
    for (std::size_t i = 0; i < n; ++i) {
      const double row[3] = {file[stride * i + 1], file[stride * i + 2], file[stride * i + 3]};
      float ref[3];
      ASSERT_TRUE(normalizeDirection(row, ref));
      for (int c = 0; c < 3; ++c) ASSERT_TRUE(sameBits(L[3 * i + c], ref[c])) << "stride " << stride << " row " << i;
      ASSERT_EQ(index[i], i % 5);
    }
  }
}

TEST(Directions, BadRowsAreCounted) {
  const float nan = std::numeric_limits<float>::quiet_NaN(), inf = std::numeric_limits<float>::infinity();
  const std::vector<float> rows = {0, 0, 1, 0, 0, 0, nan, 0, 1, 1, inf, 0, 1e-30f, 0, 0, -0.0f, 0, 0};
  std::vector<float> out(rows.size());
  // zero, NaN, inf, a length below float's range (rescaled row by row), -0
  EXPECT_EQ(detail::normalizeToRows(rows.data(), 3, 6, out.data()), 5u);
  const double tiny[3] = {1e-30, 0, 0};
  ASSERT_TRUE(brdfcl::normalizeDirection(tiny, out.data()));
  EXPECT_EQ(out[0], 1.0f);
  const std::vector<double> idx = {0, 1, 2, -1, 0.5, 3, std::nan(""), 4294967296.0};
  std::vector<std::uint32_t> got(idx.size());
  EXPECT_EQ(detail::materialIndices(idx.data(), 1, idx.size(), 3, got.data()), 5u);
  EXPECT_EQ(got[0], 0u);
  EXPECT_EQ(got[2], 2u);
}

// Against x / |v| computed in long double: within 3 ulp, and rescaling by a power of two
// changes nothing.
TEST(Directions, AccurateAndScaleInvariant) {
  const std::size_t n = 20000;
  const auto d = randomRows(n, -30, 30, 4);
  for (std::size_t i = 0; i < n; ++i) {
    const double* row = &d[3 * i];
    float got[3];
    ASSERT_TRUE(normalizeDirection(row, got));
    const long double len = std::sqrt((long double)row[0] * row[0] + (long double)row[1] * row[1] +
                                      (long double)row[2] * row[2]);
    for (int c = 0; c < 3; ++c) {
      const long double exact = row[c] / len;
      // ilogb(0) is INT_MIN: a zero component is held to the smallest normal float's ulp.
      const long double ulp = std::ldexp(1.0L, std::max(std::ilogb(float(exact)), -126) - 23);
      ASSERT_LE(std::fabs(got[c] - exact), 3 * ulp) << "row " << i << " component " << c << ": " << got[c]
                                                    << " vs " << double(exact);
    }
    for (int e : {-900, -200, 300, 900}) {
      const double scaled[3] = {std::ldexp(row[0], e), std::ldexp(row[1], e), std::ldexp(row[2], e)};
      float s[3];
      ASSERT_TRUE(normalizeDirection(scaled, s));
      for (int c = 0; c < 3; ++c) ASSERT_TRUE(sameBits(s[c], got[c])) << "row " << i << " scaled by 2^" << e;
    }
  }
  const double zero[3] = {0, -0.0, 0};
  float out[3] = {7, 7, 7};
  EXPECT_FALSE(normalizeDirection(zero, out));
  EXPECT_EQ(out[0], 7.0f);
  const double tiny[3] = {4.9e-324, 0, 0};  // the smallest subnormal still normalizes
  ASSERT_TRUE(normalizeDirection(tiny, out));
  EXPECT_EQ(out[0], 1.0f);
  const double huge[3] = {1.7e308, -1.7e308, 1.7e308};
  ASSERT_TRUE(normalizeDirection(huge, out));
  EXPECT_NEAR(out[1], -1 / std::sqrt(3.0), 1e-7);
}

}  // namespace
