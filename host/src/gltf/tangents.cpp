// Tangent generation (tangents.hpp), written for brdfcl after the MikkTSpace description: per-triangle
// tangent and bitangent from the UV derivatives, accumulated per vertex weighted by the corner angle
// after projection onto the vertex normal's plane, split by UV handedness, Gram-Schmidt at the end.
#include "gltf/tangents.hpp"

#include <array>
#include <cmath>
#include <cstdint>
#include <vector>

#include "io/vec3.hpp"

namespace brdfcl::gltf::detail {
namespace {

using V3 = Imath::V3d;

// Unit vector, or zero when a has no usable length.
V3 unit(const V3& a) {
  const double l = ::brdfcl::detail::norm(a);
  return l > 1e-20 && std::isfinite(l) ? a * (1.0 / l) : V3(0, 0, 0);
}
bool isZero(const V3& a) { return a == V3(0, 0, 0); }

// The component of t perpendicular to n (unit), normalized.
V3 tangentPlane(const V3& t, const V3& n) { return unit(t - n * (n ^ t)); }

// Any unit vector perpendicular to n: the frame for vertices whose UVs say nothing.
V3 anyPerpendicular(const V3& n) {
  const V3 axis = std::fabs(n.x) < 0.9 ? V3(1, 0, 0) : V3(0, 1, 0);
  return unit(n % axis);
}

V3 load3(const std::vector<float>& v, std::size_t i) { return V3(v[3 * i], v[3 * i + 1], v[3 * i + 2]); }

// Sums for one vertex and one UV handedness (0: as an unmirrored glTF texture, whose v runs down
// the image, is laid out: clockwise in (u, v); 1: mirrored).
struct Sum {
  V3 t{0, 0, 0}, b{0, 0, 0};
  bool used = false;
};

// Per-vertex normals: the file's, or the corner-angle-weighted face normals when it has none.
std::vector<V3> vertexNormals(const Primitive& p) {
  const std::size_t n = p.vertexCount();
  std::vector<V3> out(n, V3(0, 0, 0));
  if (!p.normals.empty()) {
    for (std::size_t i = 0; i < n; ++i) out[i] = unit(load3(p.normals, i));
  }
  for (std::size_t t = 0; t + 2 < p.indices.size(); t += 3) {
    const std::uint32_t idx[3] = {p.indices[t], p.indices[t + 1], p.indices[t + 2]};
    const V3 face = unit((load3(p.positions, idx[1]) - load3(p.positions, idx[0])) %
                         (load3(p.positions, idx[2]) - load3(p.positions, idx[0])));
    for (int k = 0; k < 3; ++k)
      if (p.normals.empty() || isZero(out[idx[k]])) out[idx[k]] = out[idx[k]] + face;
  }
  for (V3& v : out) v = unit(v);
  return out;
}

double cornerAngle(const V3& at, const V3& a, const V3& b) {
  const V3 ea = unit(a - at), eb = unit(b - at);
  if (isZero(ea) || isZero(eb)) return 0.0;
  const double c = ea ^ eb;
  return std::acos(c < -1.0 ? -1.0 : c > 1.0 ? 1.0 : c);
}

// Appends a copy of vertex v to every per-vertex array; returns its index.
std::uint32_t duplicateVertex(Primitive& p, std::uint32_t v) {
  auto copy = [v](std::vector<float>& a, std::size_t k) {
    if (a.empty()) return;
    for (std::size_t c = 0; c < k; ++c) a.push_back(a[v * k + c]);
  };
  copy(p.positions, 3);
  copy(p.normals, 3);
  copy(p.uv0, 2);
  copy(p.uv1, 2);
  copy(p.color0, 4);
  return static_cast<std::uint32_t>(p.vertexCount() - 1);
}

}  // namespace

void generateTangents(Primitive& p, int uvSet) {
  const std::vector<float>& uv = uvSet == 1 ? p.uv1 : p.uv0;
  const std::size_t n = p.vertexCount();
  if (uv.size() != 2 * n) return;
  std::vector<V3> normals = vertexNormals(p);
  std::vector<std::array<Sum, 2>> sums(n);
  std::vector<std::uint8_t> triangleSide(p.indices.size() / 3, 0);

  for (std::size_t t = 0; t + 2 < p.indices.size(); t += 3) {
    const std::uint32_t idx[3] = {p.indices[t], p.indices[t + 1], p.indices[t + 2]};
    const V3 P[3] = {load3(p.positions, idx[0]), load3(p.positions, idx[1]), load3(p.positions, idx[2])};
    const double s1 = double(uv[2 * idx[1]]) - uv[2 * idx[0]], t1 = double(uv[2 * idx[1] + 1]) - uv[2 * idx[0] + 1];
    const double s2 = double(uv[2 * idx[2]]) - uv[2 * idx[0]], t2 = double(uv[2 * idx[2] + 1]) - uv[2 * idx[0] + 1];
    const double area = s1 * t2 - s2 * t1;  // twice the signed UV area
    if (area == 0.0 || !std::isfinite(area)) continue;  // degenerate in UV: no information
    const V3 e1 = P[1] - P[0], e2 = P[2] - P[0];
    const V3 T = (e1 * t2 - e2 * t1) * (1.0 / area);  // dP/du
    const V3 B = (e2 * s1 - e1 * s2) * (1.0 / area);  // dP/dv
    const int side = area < 0 ? 0 : 1;
    triangleSide[t / 3] = std::uint8_t(side);
    for (int k = 0; k < 3; ++k) {
      const V3& nrm = normals[idx[k]];
      const V3 tp = tangentPlane(T, nrm);
      const double w = cornerAngle(P[k], P[(k + 1) % 3], P[(k + 2) % 3]);
      if (isZero(tp) || !(w > 0.0)) continue;
      Sum& s = sums[idx[k]][side];
      s.t = s.t + tp * w;
      s.b = s.b + unit(B) * w;
      s.used = true;
    }
  }

  // Mirrored triangles get their own copy of a vertex the other side also uses.
  std::vector<std::uint32_t> mirrorCopy(n, UINT32_MAX);
  std::vector<std::uint32_t> copyOrigin;  // per appended vertex
  for (std::size_t t = 0; t + 2 < p.indices.size(); t += 3) {
    if (triangleSide[t / 3] != 1) continue;
    for (int k = 0; k < 3; ++k) {
      const std::uint32_t v = p.indices[t + k];
      if (!sums[v][0].used || !sums[v][1].used) continue;
      if (mirrorCopy[v] == UINT32_MAX) {
        mirrorCopy[v] = duplicateVertex(p, v);
        copyOrigin.push_back(v);
      }
      p.indices[t + k] = mirrorCopy[v];
    }
  }

  const std::size_t total = p.vertexCount();
  p.tangents.assign(4 * total, 0.0f);
  for (std::size_t v = 0; v < total; ++v) {
    const bool isCopy = v >= n;
    const std::size_t orig = isCopy ? copyOrigin[v - n] : v;
    const std::array<Sum, 2>& both = sums[orig];
    // An original keeps side 0 when it has it; its copy always takes side 1.
    const Sum& s = isCopy ? both[1] : (both[0].used ? both[0] : both[1]);
    const V3& nrm = normals[orig];
    V3 t = tangentPlane(s.t, nrm);
    if (isZero(t)) t = isZero(nrm) ? V3(1, 0, 0) : anyPerpendicular(nrm);
    // glTF: bitangent = cross(N, T) * w points where the texture's v decreases (image up).
    const double w = ((nrm % t) ^ s.b) > 0.0 ? -1.0 : 1.0;
    for (int c = 0; c < 3; ++c) p.tangents[4 * v + c] = static_cast<float>(t[c]);
    p.tangents[4 * v + 3] = static_cast<float>(w);
  }
  p.generatedTangents = true;
}

}  // namespace brdfcl::gltf::detail
