// glTF material decode at a hit: interpolated attributes, tangent frame (TANGENT, else the hit
// triangle's UV derivative), normal and clearcoat normal maps, factors times texels, and the
// anisotropy direction expressed about the final shading frame. Conventions in docs/gltf.md.
#include "gltf/surface.hpp"

#include <algorithm>
#include <cmath>

#include "io/vec3.hpp"

namespace brdfcl::gltf {
namespace {

using V3 = Imath::V3f;
using brdfcl::detail::norm;
using brdfcl::detail::toArray;
using brdfcl::detail::toVec3;

// Unit vector, or false for a zero, tiny or non-finite input.
bool normalize(V3& a) {
  const float len = norm(a);
  if (!(len > 1e-20f) || !std::isfinite(len)) return false;
  a = (1.0f / len) * a;
  return true;
}
float clamp01(float x) { return std::clamp(x, 0.0f, 1.0f); }  // NaN stays NaN; factors are finite

V3 vertex3(const std::vector<float>& a, std::uint32_t i) { return V3(a[3 * i], a[3 * i + 1], a[3 * i + 2]); }

// T perpendicular to N (unit N); the frame of docs/gbuffer.md when T is missing or parallel to N.
V3 orthoTangent(V3 T, V3 N) {
  V3 t = T - (N ^ T) * N;
  if (normalize(t)) return t;
  const V3 b0 = std::fabs(N.y) > 0.999f ? V3(1, 0, 0) : V3(0, 1, 0);
  t = b0 % N;
  normalize(t);
  return t;
}

struct Triangle {
  std::uint32_t i0, i1, i2;
  float b0, b1, b2;
  V3 p0, p1, p2, e1, e2, Ng;  // Ng: unit, from the counter-clockwise winding
  float area2;                // |e1 x e2|
};

Triangle triangle(const Primitive& p, const Hit& h) {
  Triangle t;
  t.i0 = p.indices[3 * h.tri];
  t.i1 = p.indices[3 * h.tri + 1];
  t.i2 = p.indices[3 * h.tri + 2];
  t.b1 = h.u;
  t.b2 = h.v;
  t.b0 = 1.0f - h.u - h.v;
  t.p0 = vertex3(p.positions, t.i0);
  t.p1 = vertex3(p.positions, t.i1);
  t.p2 = vertex3(p.positions, t.i2);
  t.e1 = t.p1 - t.p0;
  t.e2 = t.p2 - t.p0;
  t.Ng = t.e1 % t.e2;
  t.area2 = norm(t.Ng);
  if (!normalize(t.Ng)) t.Ng = -toVec3(h.dir);
  return t;
}

struct Uv {
  float u = 0, v = 0;
  float coneLod = 0;  // Δ_tri + log2(width / |cos θ|) for this UV set
  float du1 = 0, dv1 = 0, du2 = 0, dv2 = 0;
  bool present = false;
};

Uv uvSet(const std::vector<float>& uv, const Triangle& t, std::size_t vertexCount, float footprint) {
  Uv r;
  if (uv.size() < 2 * vertexCount) return r;
  r.present = true;
  const float u0 = uv[2 * t.i0], v0 = uv[2 * t.i0 + 1], u1 = uv[2 * t.i1], v1 = uv[2 * t.i1 + 1];
  const float u2 = uv[2 * t.i2], v2 = uv[2 * t.i2 + 1];
  r.u = t.b0 * u0 + t.b1 * u1 + t.b2 * u2;
  r.v = t.b0 * v0 + t.b1 * v1 + t.b2 * v2;
  r.du1 = u1 - u0;
  r.dv1 = v1 - v0;
  r.du2 = u2 - u0;
  r.dv2 = v2 - v0;
  const float uvArea2 = std::fabs(r.du1 * r.dv2 - r.du2 * r.dv1);
  // A triangle without UV extent reads one texel footprint-free: -inf selects magnification.
  r.coneLod = 0.5f * std::log2(uvArea2 / t.area2) + footprint;
  return r;
}

}  // namespace

Surfaces::Surfaces(const Asset& asset, const Textures& textures) : asset_(asset), textures_(textures) {}

const Material& Surfaces::material(int prim) const {
  const int m = asset_.primitives[prim].material;
  return m >= 0 && m < static_cast<int>(asset_.materials.size()) ? asset_.materials[m] : default_;
}

bool Surfaces::mayReject(int prim) const {
  const Material& m = material(prim);
  return !m.doubleSided || m.alphaMode != AlphaMode::Opaque;
}

bool Surfaces::accepts(const Hit& h) const {
  const Material& m = material(h.prim);
  const Primitive& p = asset_.primitives[h.prim];
  const Triangle t = triangle(p, h);
  const V3 dir = toVec3(h.dir);
  const float cosTheta = t.Ng ^ dir;
  if (!m.doubleSided && cosTheta > 0.0f) return false;
  if (m.alphaMode == AlphaMode::Opaque) return true;
  float alpha = clamp01(m.baseColorFactor[3]);
  if (m.baseColorTexture.present()) {
    const float footprint = std::log2(h.coneWidth / std::max(std::fabs(cosTheta), 1e-4f));
    const Uv uv = uvSet(m.baseColorTexture.texCoord == 1 ? p.uv1 : p.uv0, t, p.vertexCount(), footprint);
    alpha *= textures_.sample(m.baseColorTexture, ColorSpace::Srgb, uv.u, uv.v, uv.coneLod)[3];
  }
  if (p.color0.size() >= 4 * p.vertexCount())
    alpha *= t.b0 * p.color0[4 * t.i0 + 3] + t.b1 * p.color0[4 * t.i1 + 3] + t.b2 * p.color0[4 * t.i2 + 3];
  const float cutoff = m.alphaMode == AlphaMode::Mask ? m.alphaCutoff : 0.5f;
  return alpha >= cutoff;
}

namespace {
// A hit's texture lookups. Slots often share a texture (occlusion and metallic-roughness in one
// ORM image, clearcoat and its roughness): such a texture is sampled once per hit.
class HitSampler {
 public:
  HitSampler(const Textures& textures, const Uv (&uvs)[2]) : textures_(textures), uvs_(uvs) {}

  std::array<float, 4> operator()(const TextureRef& ref, ColorSpace space) {
    for (int k = 0; k < doneCount_; ++k) {
      const TextureRef& r = *done_[k].ref;
      if (r.texture == ref.texture && done_[k].space == space && r.texCoord == ref.texCoord &&
          r.transform.offset == ref.transform.offset && r.transform.rotation == ref.transform.rotation &&
          r.transform.scale == ref.transform.scale)
        return done_[k].value;
    }
    const Uv& uv = uvs_[ref.texCoord == 1 ? 1 : 0];
    const std::array<float, 4> value = textures_.sample(ref, space, uv.u, uv.v, uv.coneLod);
    if (doneCount_ < 12) done_[doneCount_++] = {&ref, space, value};
    return value;
  }

 private:
  struct Sampled {
    const TextureRef* ref;
    ColorSpace space;
    std::array<float, 4> value;
  };
  const Textures& textures_;
  const Uv (&uvs_)[2];
  Sampled done_[12];
  int doneCount_ = 0;
};

// The shading frame at a hit: normal, tangent, bitangent and the bitangent's sign w.
struct Frame {
  V3 N, T, B;
  float w;
};

Frame hitFrame(const Material& m, const Primitive& p, const Triangle& t, const Uv (&uvs)[2], float cosTheta) {
  const std::size_t vc = p.vertexCount();
  V3 Ng = t.Ng, N = Ng;
  if (p.normals.size() >= 3 * vc) {
    N = t.b0 * vertex3(p.normals, t.i0) + t.b1 * vertex3(p.normals, t.i1) + t.b2 * vertex3(p.normals, t.i2);
    if (!normalize(N)) N = Ng;
  }

  // Tangent and bitangent sign: TANGENT, else +u and -v (image up, the normal map's +Y) of the
  // hit triangle's UV set that the normal map reads.
  V3 T(0, 0, 0);
  float w = 1.0f;
  if (p.tangents.size() >= 4 * vc) {
    const auto tan4 = [&](std::uint32_t i) { return V3(p.tangents[4 * i], p.tangents[4 * i + 1], p.tangents[4 * i + 2]); };
    T = t.b0 * tan4(t.i0) + t.b1 * tan4(t.i1) + t.b2 * tan4(t.i2);
    w = p.tangents[4 * t.i0 + 3] < 0.0f ? -1.0f : 1.0f;
  } else {
    const TextureRef& ref = m.normalTexture.present()            ? m.normalTexture
                            : m.clearcoatNormalTexture.present() ? m.clearcoatNormalTexture
                                                                 : m.anisotropyTexture;
    const Uv& uv = uvs[ref.texCoord == 1 ? 1 : 0];
    // The map's texel axes are those of the transformed UVs (KHR_texture_transform's rotation
    // and scale; the offset drops out of the differences).
    const TextureTransform& tr = ref.transform;
    const float c = std::cos(tr.rotation), sn = std::sin(tr.rotation);
    const float du1 = c * tr.scale[0] * uv.du1 + sn * tr.scale[1] * uv.dv1;
    const float dv1 = -sn * tr.scale[0] * uv.du1 + c * tr.scale[1] * uv.dv1;
    const float du2 = c * tr.scale[0] * uv.du2 + sn * tr.scale[1] * uv.dv2;
    const float dv2 = -sn * tr.scale[0] * uv.du2 + c * tr.scale[1] * uv.dv2;
    const float det = du1 * dv2 - du2 * dv1;
    if (uv.present && std::fabs(det) > 0.0f) {
      T = (1.0f / det) * (dv2 * t.e1 - dv1 * t.e2);
      const V3 dPdv = (1.0f / det) * (du1 * t.e2 - du2 * t.e1);
      w = ((N % T) ^ -dPdv) < 0.0f ? -1.0f : 1.0f;
    }
  }
  // Double-sided back faces are shaded from behind: the whole frame turns to the viewer
  // (as the Khronos sample viewer does: t, b and ng negated).
  if (cosTheta > 0.0f) {
    N = -N;
    Ng = -Ng;
    T = -T;
    w = -w;
  }
  T = orthoTangent(T, N);
  return {N, T, w * (N % T), w};
}

// The normal a normal map gives in `frame`, or the frame's normal where the texel has none.
V3 mapNormal(const TextureRef& ref, const Frame& frame, HitSampler& sample) {
  const std::array<float, 4> c = sample(ref, ColorSpace::Linear);
  V3 n((2.0f * c[0] - 1.0f) * ref.value, (2.0f * c[1] - 1.0f) * ref.value, 2.0f * c[2] - 1.0f);
  if (!normalize(n)) return frame.N;
  V3 mapped = n.x * frame.T + n.y * frame.B + n.z * frame.N;
  return normalize(mapped) ? mapped : frame.N;
}

// Base colour (with COLOR_0), metallic, roughness and occlusion of `s`.
void baseLayer(SurfacePoint& s, const Material& m, const Primitive& p, const Triangle& t, HitSampler& sample) {
  std::array<float, 3> base{clamp01(m.baseColorFactor[0]), clamp01(m.baseColorFactor[1]), clamp01(m.baseColorFactor[2])};
  if (m.baseColorTexture.present()) {
    const std::array<float, 4> c = sample(m.baseColorTexture, ColorSpace::Srgb);
    for (int k = 0; k < 3; ++k) base[k] *= c[k];
  }
  if (p.color0.size() >= 4 * p.vertexCount())
    for (int k = 0; k < 3; ++k)
      base[k] *= clamp01(t.b0 * p.color0[4 * t.i0 + k] + t.b1 * p.color0[4 * t.i1 + k] + t.b2 * p.color0[4 * t.i2 + k]);
  s.baseColor = base;

  s.metallic = clamp01(m.metallicFactor);
  s.roughness = clamp01(m.roughnessFactor);
  if (m.metallicRoughnessTexture.present()) {
    const std::array<float, 4> c = sample(m.metallicRoughnessTexture, ColorSpace::Linear);
    s.metallic *= c[2];
    s.roughness *= c[1];
  }
  if (m.occlusionTexture.present())
    s.occlusion = 1.0f + clamp01(m.occlusionTexture.value) * (sample(m.occlusionTexture, ColorSpace::Linear)[0] - 1.0f);
}

// Emission, sheen and clearcoat of `s`.
void extensionLayers(SurfacePoint& s, const Material& m, HitSampler& sample) {
  const float strength = std::max(0.0f, m.emissiveStrength);
  s.emissive = {strength * clamp01(m.emissiveFactor[0]), strength * clamp01(m.emissiveFactor[1]),
                strength * clamp01(m.emissiveFactor[2])};
  if (m.emissiveTexture.present()) {
    const std::array<float, 4> c = sample(m.emissiveTexture, ColorSpace::Srgb);
    for (int k = 0; k < 3; ++k) s.emissive[k] *= c[k];
  }

  s.sheenColor = {clamp01(m.sheenColorFactor[0]), clamp01(m.sheenColorFactor[1]), clamp01(m.sheenColorFactor[2])};
  if (m.sheenColorTexture.present()) {
    const std::array<float, 4> c = sample(m.sheenColorTexture, ColorSpace::Srgb);
    for (int k = 0; k < 3; ++k) s.sheenColor[k] *= c[k];
  }
  s.sheenRoughness = clamp01(m.sheenRoughnessFactor);
  if (m.sheenRoughnessTexture.present()) s.sheenRoughness *= sample(m.sheenRoughnessTexture, ColorSpace::Linear)[3];

  s.clearcoat = clamp01(m.clearcoatFactor);
  if (m.clearcoatTexture.present()) s.clearcoat *= sample(m.clearcoatTexture, ColorSpace::Linear)[0];
  s.clearcoatRoughness = clamp01(m.clearcoatRoughnessFactor);
  if (m.clearcoatRoughnessTexture.present())
    s.clearcoatRoughness *= sample(m.clearcoatRoughnessTexture, ColorSpace::Linear)[1];
}
}  // namespace

SurfacePoint Surfaces::evaluate(const Hit& h) const {
  const Material& m = material(h.prim);
  const Primitive& p = asset_.primitives[h.prim];
  const std::size_t vc = p.vertexCount();
  const Triangle t = triangle(p, h);
  const V3 dir = toVec3(h.dir);
  SurfacePoint s;
  s.P = toArray(t.b0 * t.p0 + t.b1 * t.p1 + t.b2 * t.p2);

  const float cosTheta = t.Ng ^ dir;
  const float footprint = std::log2(h.coneWidth / std::max(std::fabs(cosTheta), 1e-4f));
  const Uv uvs[2] = {uvSet(p.uv0, t, vc, footprint), uvSet(p.uv1, t, vc, footprint)};
  HitSampler sample(textures_, uvs);
  const Frame frame = hitFrame(m, p, t, uvs, cosTheta);

  const V3 Nmapped = m.normalTexture.present() ? mapNormal(m.normalTexture, frame, sample) : frame.N;
  s.N = toArray(Nmapped);
  s.clearcoatN = toArray(m.clearcoatNormalTexture.present() ? mapNormal(m.clearcoatNormalTexture, frame, sample) : frame.N);
  baseLayer(s, m, p, t, sample);
  extensionLayers(s, m, sample);

  // KHR_materials_anisotropy: the direction lives in the (T, B) plane with B = w N x T; the
  // G-buffer angle is about N from T towards N x T, so the sign w folds into it.
  float rotation = m.anisotropyRotation;
  s.anisotropyStrength = clamp01(m.anisotropyStrength);
  if (m.anisotropyTexture.present()) {
    const std::array<float, 4> c = sample(m.anisotropyTexture, ColorSpace::Linear);
    const float dx = 2.0f * c[0] - 1.0f, dy = 2.0f * c[1] - 1.0f;
    if (dx != 0.0f || dy != 0.0f) rotation += std::atan2(dy, dx);
    s.anisotropyStrength *= c[2];
  }
  s.anisotropyRotation = frame.w * rotation;
  s.T = toArray(orthoTangent(frame.T, Nmapped));
  return s;
}

}  // namespace brdfcl::gltf
