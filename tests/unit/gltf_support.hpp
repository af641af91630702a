// Test support for the glTF ray caster: in-memory assets (quads, images, cameras), matrices,
// an independent sRGB decode, and the G-buffer invariants every traced image must satisfy.
#pragma once
#include <gtest/gtest.h>

#include <cmath>
#include <functional>

#include "brdfcl/error.hpp"
#include "brdfcl/gltf.hpp"
#include "brdfcl/gltf_render.hpp"

namespace brdfcl::test {

using gltf::Mat4;

inline Mat4 identity() { return {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1}; }
inline Mat4 translation(double x, double y, double z) {
  Mat4 m = identity();
  m[12] = x;
  m[13] = y;
  m[14] = z;
  return m;
}
inline Mat4 rotationY(double a) {  // column-major
  Mat4 m = identity();
  m[0] = std::cos(a);
  m[2] = -std::sin(a);
  m[8] = std::sin(a);
  m[10] = std::cos(a);
  return m;
}
inline Mat4 rotationX(double a) {
  Mat4 m = identity();
  m[5] = std::cos(a);
  m[6] = std::sin(a);
  m[9] = -std::sin(a);
  m[10] = std::cos(a);
  return m;
}
inline Mat4 scaling(double s) {
  Mat4 m = identity();
  m[0] = m[5] = m[10] = s;
  return m;
}
inline Mat4 mul(const Mat4& a, const Mat4& b) {
  Mat4 r{};
  for (int c = 0; c < 4; ++c)
    for (int rr = 0; rr < 4; ++rr)
      for (int k = 0; k < 4; ++k) r[c * 4 + rr] += a[k * 4 + rr] * b[c * 4 + k];
  return r;
}
inline std::array<double, 3> apply(const Mat4& m, std::array<double, 3> p) {
  return {m[0] * p[0] + m[4] * p[1] + m[8] * p[2] + m[12], m[1] * p[0] + m[5] * p[1] + m[9] * p[2] + m[13],
          m[2] * p[0] + m[6] * p[1] + m[10] * p[2] + m[14]};
}

// IEC 61966-2-1, written out here so the tests do not share the implementation's decode.
inline double srgbDecode(double c) { return c <= 0.04045 ? c / 12.92 : std::pow((c + 0.055) / 1.055, 2.4); }

// An axis-aligned quad in the plane z, front face towards +Z (or -Z), UV (0,0) at the top-left
// corner (x0, y1) and (1,1) at (x1, y0); normals along the front face; optional tangents +X.
inline gltf::Primitive quad(double x0, double y0, double x1, double y1, double z, int material, bool frontPlusZ = true,
                            bool withNormals = true) {
  gltf::Primitive p;
  p.material = material;
  p.where = "quad";
  const float X0 = float(x0), X1 = float(x1), Y0 = float(y0), Y1 = float(y1), Z = float(z);
  p.positions = {X0, Y1, Z, X1, Y1, Z, X0, Y0, Z, X1, Y0, Z};  // TL, TR, BL, BR
  p.uv0 = {0, 0, 1, 0, 0, 1, 1, 1};
  const float nz = frontPlusZ ? 1.0f : -1.0f;
  if (withNormals) p.normals = {0, 0, nz, 0, 0, nz, 0, 0, nz, 0, 0, nz};
  // Counter-clockwise seen from +Z: BL, BR, TR and BL, TR, TL.
  if (frontPlusZ)
    p.indices = {2, 3, 1, 2, 1, 0};
  else
    p.indices = {2, 1, 3, 2, 0, 1};
  return p;
}

// 8-bit texel values widened as the loader does (v * 257).
inline gltf::Image image(int w, int h, const std::function<int(int x, int y, int c)>& value) {
  gltf::Image im;
  im.name = "test";
  im.width = w;
  im.height = h;
  im.rgba.resize(std::size_t(w) * h * 4);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x)
      for (int c = 0; c < 4; ++c) im.rgba[(std::size_t(y) * w + x) * 4 + c] = std::uint16_t(value(x, y, c) * 257);
  return im;
}

// An orthographic camera at (0, 0, distance) looking down -Z, its image plane ymag high.
inline gltf::Camera frontOrtho(double ymag = 1.0, double distance = 5.0) {
  gltf::Camera c;
  c.index = 0;
  c.node = 0;
  c.name = "front";
  c.orthographic = true;
  c.xmag = ymag;
  c.ymag = ymag;
  c.znear = 0.01;
  c.zfar = 100;
  c.world = translation(0, 0, distance);
  return c;
}

inline float len3(const std::vector<float>& v, std::size_t i) {
  return std::sqrt(v[3 * i] * v[3 * i] + v[3 * i + 1] * v[3 * i + 1] + v[3 * i + 2] * v[3 * i + 2]);
}

// docs/gbuffer.md: finite channels, unit N/T/clearcoatN/V on hits, T perpendicular to N, misses 0 but V.
inline void expectValid(const GBuffer& g) {
  const std::size_t n = g.pixelCount();
  for (const std::vector<float>* v : {&g.P, &g.N, &g.T, &g.baseColor, &g.emissive, &g.sheenColor, &g.clearcoatN, &g.V})
    ASSERT_EQ(v->size(), 3 * n);
  for (const std::vector<float>* v : {&g.metallic, &g.roughness, &g.mask, &g.sheenRoughness, &g.clearcoat,
                                      &g.clearcoatRoughness, &g.anisotropyStrength, &g.anisotropyRotation, &g.occlusion})
    ASSERT_EQ(v->size(), n);
  for (std::size_t i = 0; i < n; ++i) {
    ASSERT_NEAR(len3(g.V, i), 1.0f, 1e-5f) << "pixel " << i;
    if (g.mask[i] == 0.0f) {
      ASSERT_EQ(len3(g.N, i), 0.0f) << "miss pixel " << i;
      ASSERT_EQ(g.baseColor[3 * i], 0.0f);
      continue;
    }
    ASSERT_EQ(g.mask[i], 1.0f);
    ASSERT_NEAR(len3(g.N, i), 1.0f, 1e-5f) << "pixel " << i;
    ASSERT_NEAR(len3(g.T, i), 1.0f, 1e-5f) << "pixel " << i;
    ASSERT_NEAR(len3(g.clearcoatN, i), 1.0f, 1e-5f) << "pixel " << i;
    const float nt = g.N[3 * i] * g.T[3 * i] + g.N[3 * i + 1] * g.T[3 * i + 1] + g.N[3 * i + 2] * g.T[3 * i + 2];
    ASSERT_NEAR(nt, 0.0f, 1e-5f) << "pixel " << i;
    for (const std::vector<float>* v : {&g.P, &g.baseColor, &g.emissive, &g.sheenColor})
      for (int k = 0; k < 3; ++k) ASSERT_TRUE(std::isfinite((*v)[3 * i + k]));
    for (const std::vector<float>* v : {&g.metallic, &g.roughness, &g.sheenRoughness, &g.clearcoat,
                                        &g.clearcoatRoughness, &g.anisotropyStrength, &g.anisotropyRotation, &g.occlusion})
      ASSERT_TRUE(std::isfinite((*v)[i]));
  }
}

}  // namespace brdfcl::test
