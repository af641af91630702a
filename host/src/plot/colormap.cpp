// The diverging and sequential colour maps. Control points were chosen in CIELAB (D65): the
// diverging map runs L* 40 -> 96 -> 40 with chroma falling to 0 at the centre (hue 282 deg blue,
// 35 deg red); the sequential map runs L* 18 -> 93 in even steps while the hue turns from violet
// (305 deg) to yellow (100 deg). Points are close enough that linear-RGB interpolation between
// them keeps lightness monotonic on each side (checked in tests/unit/test_image_diff.cpp).
#include <algorithm>
#include <array>
#include <cmath>
#include <iterator>

#include "brdfcl/image.hpp"
#include "plot/plot.hpp"

namespace brdfcl::plot {

namespace {
using Hex = std::array<std::uint8_t, 3>;

constexpr Hex kDiverging[] = {
    {0x0f, 0x5e, 0xb2}, {0x62, 0x80, 0xc3}, {0x96, 0xa5, 0xd3}, {0xc5, 0xcb, 0xe4}, {0xf3, 0xf3, 0xf3},
    {0xe9, 0xc4, 0xbc}, {0xda, 0x94, 0x88}, {0xc5, 0x65, 0x57}, {0xac, 0x32, 0x29},
};
constexpr Hex kSequential[] = {
    {0x30, 0x23, 0x57}, {0x25, 0x3c, 0x7d}, {0x00, 0x58, 0x8e}, {0x15, 0x73, 0x91}, {0x2b, 0x8e, 0x95},
    {0x2f, 0xab, 0x8a}, {0x70, 0xc3, 0x6c}, {0xb8, 0xd9, 0x47}, {0xfc, 0xef, 0x44},
};

double decodeSrgb(std::uint8_t v) {
  const double e = v / 255.0;
  return e <= 0.04045 ? e / 12.92 : std::pow((e + 0.055) / 1.055, 2.4);
}

template <std::size_t N>
struct Linear {
  double rgb[N][3];
  explicit Linear(const Hex (&points)[N]) {
    for (std::size_t i = 0; i < N; ++i)
      for (int c = 0; c < 3; ++c) rgb[i][c] = decodeSrgb(points[i][c]);
  }
};

template <std::size_t N>
Colour interpolate(const Hex (&points)[N], const Linear<N>& linear, double t) {
  const double x = t * double(N - 1);
  const std::size_t i = std::min(static_cast<std::size_t>(x), N - 2);
  const double f = x - double(i);
  // The control points must come out exactly as defined (tests compare them): no round trip.
  if (f == 0.0) return {points[i][0], points[i][1], points[i][2]};
  if (f == 1.0) return {points[i + 1][0], points[i + 1][1], points[i + 1][2]};
  std::uint8_t out[3];
  for (int c = 0; c < 3; ++c)
    out[c] = encodeSrgb8(static_cast<float>((1.0 - f) * linear.rgb[i][c] + f * linear.rgb[i + 1][c]));
  return {out[0], out[1], out[2]};
}
}  // namespace

Colour mapColour(ColourMap map, double t) {
  if (std::isnan(t)) return kNotFinite;
  t = std::fmin(std::fmax(t, 0.0), 1.0);
  static const Linear<std::size(kDiverging)> diverging(kDiverging);
  static const Linear<std::size(kSequential)> sequential(kSequential);
  return map == ColourMap::Diverging ? interpolate(kDiverging, diverging, t) : interpolate(kSequential, sequential, t);
}

}  // namespace brdfcl::plot
