// The loader's walk of the chosen scene (loader.cpp calls buildScene): node graph checks, world
// matrices in double precision, primitives expanded into world-space triangle lists, cameras and
// lights placed, and the warnings for what brdfcl leaves out.
#include <tiny_gltf.h>

#include <algorithm>
#include <cmath>
#include <numeric>
#include <string>
#include <utility>
#include <vector>

#include "brdfcl/error.hpp"
#include "brdfcl/gltf.hpp"
#include "gltf/accessors.hpp"
#include "gltf/document.hpp"
#include "gltf/tangents.hpp"
#include "io/messages.hpp"
#include "io/option_style.hpp"

namespace brdfcl::gltf::detail {
namespace {

std::string at(const char* kind, std::size_t i) { return std::string(kind) + "[" + std::to_string(i) + "]"; }

Mat4 identity() { return {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1}; }

Mat4 multiply(const Mat4& a, const Mat4& b) {  // column-major a * b
  Mat4 r{};
  for (int c = 0; c < 4; ++c)
    for (int row = 0; row < 4; ++row) {
      double s = 0;
      for (int k = 0; k < 4; ++k) s += a[k * 4 + row] * b[c * 4 + k];
      r[c * 4 + row] = s;
    }
  return r;
}

bool finite(const Mat4& m) {
  return std::all_of(m.begin(), m.end(), [](double v) { return std::isfinite(v); });
}

// The node's local matrix: `matrix`, or translation * rotation * scale.
Mat4 localMatrix(const tinygltf::Node& n, std::size_t i, const Document& doc) {
  const std::string path = at("nodes", i);
  if (!n.matrix.empty()) {
    if (n.matrix.size() != 16) doc.fail(path + ".matrix", "expected 16 numbers, got " + std::to_string(n.matrix.size()));
    Mat4 m{};
    std::copy(n.matrix.begin(), n.matrix.end(), m.begin());
    if (!finite(m)) doc.fail(path + ".matrix", "has a non-finite number; fix the node's transform");
    return m;
  }
  auto sized = [&](const std::vector<double>& v, std::size_t k, const char* key) {
    if (!v.empty() && v.size() != k)
      doc.fail(path + "." + key, "expected " + std::to_string(k) + " numbers, got " + std::to_string(v.size()));
    return !v.empty();
  };
  const double t[3] = {sized(n.translation, 3, "translation") ? n.translation[0] : 0.0,
                       n.translation.empty() ? 0.0 : n.translation[1], n.translation.empty() ? 0.0 : n.translation[2]};
  const bool hasS = sized(n.scale, 3, "scale");
  const double s[3] = {hasS ? n.scale[0] : 1.0, hasS ? n.scale[1] : 1.0, hasS ? n.scale[2] : 1.0};
  double q[4] = {0, 0, 0, 1};
  if (sized(n.rotation, 4, "rotation")) {
    const double len = std::sqrt(n.rotation[0] * n.rotation[0] + n.rotation[1] * n.rotation[1] +
                                 n.rotation[2] * n.rotation[2] + n.rotation[3] * n.rotation[3]);
    if (!(len > 0.0) || !std::isfinite(len))
      doc.fail(path + ".rotation", "the quaternion has zero or non-finite length; use a unit quaternion");
    for (int k = 0; k < 4; ++k) q[k] = n.rotation[std::size_t(k)] / len;  // exporters round to a few digits
  }
  const double x = q[0], y = q[1], z = q[2], w = q[3];
  const double r[9] = {1 - 2 * (y * y + z * z), 2 * (x * y + z * w),     2 * (x * z - y * w),
                       2 * (x * y - z * w),     1 - 2 * (x * x + z * z), 2 * (y * z + x * w),
                       2 * (x * z + y * w),     2 * (y * z - x * w),     1 - 2 * (x * x + y * y)};  // columns
  Mat4 m{};
  for (int c = 0; c < 3; ++c)
    for (int row = 0; row < 3; ++row) m[c * 4 + row] = r[c * 3 + row] * s[c];
  m[12] = t[0];
  m[13] = t[1];
  m[14] = t[2];
  m[15] = 1;
  if (!finite(m)) doc.fail(path, "the transform has a non-finite number; fix the node's transform");
  return m;
}

// The node graph must be a forest: one parent at most, no cycles. Returns each node's parent.
std::vector<int> checkGraph(const tinygltf::Model& model, const Document& doc) {
  const std::size_t n = model.nodes.size();
  std::vector<int> parent(n, -1);
  for (std::size_t i = 0; i < n; ++i)
    for (int c : model.nodes[i].children) {
      if (c < 0 || std::size_t(c) >= n)
        doc.fail(at("nodes", i) + ".children", "node " + std::to_string(c) + " does not exist (the file has " +
                                                   std::to_string(n) + "); re-export the file");
      if (parent[std::size_t(c)] >= 0 || std::size_t(c) == i)
        doc.fail(at("nodes", std::size_t(c)), "has two parents (nodes[" + std::to_string(parent[std::size_t(c)] >= 0 ? parent[std::size_t(c)] : c) +
                                                  "] and nodes[" + std::to_string(i) +
                                                  "]) or is its own child; the node hierarchy must be a tree: re-export the file");
      parent[std::size_t(c)] = int(i);
    }
  // With one parent each, a cycle is found by walking up: reaching a node of the same walk.
  std::vector<std::size_t> walk(n, SIZE_MAX);
  std::vector<bool> done(n, false);
  for (std::size_t i = 0; i < n; ++i) {
    std::size_t v = i;
    while (!done[v]) {
      if (walk[v] == i)
        doc.fail(at("nodes", v), "is its own ancestor (a cycle in \"children\"); the node hierarchy must be a tree: re-export the file");
      walk[v] = i;
      if (parent[v] < 0) break;
      v = std::size_t(parent[v]);
    }
    for (v = i; !done[v]; v = std::size_t(parent[v])) {
      done[v] = true;
      if (parent[v] < 0) break;
    }
  }
  return parent;
}

struct Walk {
  const tinygltf::Model& model;
  const Document& doc;
  const LoadOptions& options;
  Asset& asset;
  int variant = -1;
  std::size_t used = 0;  // vertices + triangles so far, against options.maxElements
  std::size_t skippedLines = 0;
  bool skins = false, morphs = false;

  std::size_t remaining() const { return options.maxElements - std::min(used, options.maxElements); }
  void take(std::size_t n, const std::string& where) {
    if (n > remaining())
      doc.fail(where, "the scene has more than " + std::to_string(options.maxElements) +
                          " vertices and triangles, brdfcl's limit; simplify the model");
    used += n;
  }

  void node(std::size_t i, const Mat4& world);
  void primitive(std::size_t mesh, std::size_t p, std::size_t node, const Mat4& world);
  Primitive assemble(const tinygltf::Primitive& prim, const std::string& where, int mode);
};

std::vector<std::uint32_t> triangulate(const std::vector<std::uint32_t>& v, int mode) {
  std::vector<std::uint32_t> out;
  const std::size_t n = v.size();
  if (mode == TINYGLTF_MODE_TRIANGLES) {
    out.assign(v.begin(), v.begin() + std::ptrdiff_t(n - n % 3));
  } else if (n >= 3) {
    out.reserve(3 * (n - 2));
    for (std::size_t i = 0; i + 2 < n; ++i) {
      if (mode == TINYGLTF_MODE_TRIANGLE_STRIP)  // every other triangle flips to keep the winding
        out.insert(out.end(), {v[i], v[i + 1 + i % 2], v[i + 2 - i % 2]});
      else
        out.insert(out.end(), {v[i + 1], v[i + 2], v[0]});
    }
  }
  return out;
}

Primitive Walk::assemble(const tinygltf::Primitive& prim, const std::string& where, int mode) {
  const auto attr = [&](const char* name) {
    const auto it = prim.attributes.find(name);
    return it == prim.attributes.end() ? -1 : it->second;
  };
  const std::string& src = doc.source();
  if (attr("POSITION") < 0) doc.fail(where + ".attributes", "no POSITION; every triangle primitive needs one: re-export the file");
  auto exists = [&](int a, const std::string& path) {
    if (a >= 0 && std::size_t(a) >= model.accessors.size())
      doc.fail(path, "accessor " + std::to_string(a) + " does not exist (the file has " +
                         std::to_string(model.accessors.size()) + "); re-export the file");
  };
  for (const auto& [name, a] : prim.attributes) exists(a, where + ".attributes." + brdfcl::detail::printable(name, 60));
  exists(prim.indices, where + ".indices");
  Decoded pos = readAccessor(model, attr("POSITION"), {3}, "POSITION", src, remaining());
  const std::size_t n = pos.count;
  take(n, where);
  Primitive out;
  out.positions = std::move(pos.values);
  auto optional = [&](const char* name, std::initializer_list<int> allowed) {
    const int a = attr(name);
    if (a < 0) return Decoded{};
    Decoded d = readAccessor(model, a, allowed, name, src, n);
    if (d.count != n)
      doc.fail(at("accessors", std::size_t(a)), std::string(name) + " has " + std::to_string(d.count) +
                                                    " elements, POSITION has " + std::to_string(n) + "; re-export the file");
    return d;
  };
  out.normals = optional("NORMAL", {3}).values;
  out.tangents = optional("TANGENT", {4}).values;
  out.uv0 = optional("TEXCOORD_0", {2}).values;
  out.uv1 = optional("TEXCOORD_1", {2}).values;
  Decoded color = optional("COLOR_0", {3, 4});
  if (color.components == 3) {
    out.color0.reserve(4 * n);
    for (std::size_t i = 0; i < n; ++i)
      out.color0.insert(out.color0.end(), {color.values[3 * i], color.values[3 * i + 1], color.values[3 * i + 2], 1.0f});
  } else {
    out.color0 = std::move(color.values);
  }
  std::vector<std::uint32_t> order;
  if (prim.indices >= 0) {
    order = readIndices(model, prim.indices, n, src, remaining());
  } else {
    order.resize(n);
    std::iota(order.begin(), order.end(), 0u);
  }
  out.indices = triangulate(order, mode);
  take(out.indices.size() / 3, where);
  return out;
}

// Which UV set the tangent frame follows: the normal map's, else the clearcoat normal map's, else
// the anisotropy texture's, else TEXCOORD_0.
int tangentUvSet(const Material& m) {
  if (m.normalTexture.present()) return m.normalTexture.texCoord;
  if (m.clearcoatNormalTexture.present()) return m.clearcoatNormalTexture.texCoord;
  if (m.anisotropyTexture.present()) return m.anisotropyTexture.texCoord;
  return 0;
}

// Positions, normals and tangents into world space; false when the transform is singular (a node
// scaled to zero, which hides its meshes).
bool toWorld(Primitive& p, const Mat4& m) {
  auto L = [&](int r, int c) { return m[c * 4 + r]; };
  const double det = L(0, 0) * (L(1, 1) * L(2, 2) - L(2, 1) * L(1, 2)) - L(0, 1) * (L(1, 0) * L(2, 2) - L(2, 0) * L(1, 2)) +
                     L(0, 2) * (L(1, 0) * L(2, 1) - L(2, 0) * L(1, 1));
  if (!(std::fabs(det) > 0.0) || !std::isfinite(det)) return false;
  // Inverse transpose of the upper 3x3: cofactors over the determinant (the sign matters).
  double nm[3][3];
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 3; ++c) {
      const int r1 = (r + 1) % 3, r2 = (r + 2) % 3, c1 = (c + 1) % 3, c2 = (c + 2) % 3;
      nm[r][c] = (L(r1, c1) * L(r2, c2) - L(r1, c2) * L(r2, c1)) / det;
    }
  auto normalize3 = [](double v[3], float* out) {
    const double len = std::sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
    for (int k = 0; k < 3; ++k) out[k] = len > 0 && std::isfinite(len) ? float(v[k] / len) : 0.0f;
  };
  for (std::size_t i = 0; i < p.vertexCount(); ++i) {
    float* q = &p.positions[3 * i];
    double w[3];
    for (int r = 0; r < 3; ++r) w[r] = L(r, 0) * q[0] + L(r, 1) * q[1] + L(r, 2) * q[2] + L(r, 3);
    for (int r = 0; r < 3; ++r) q[r] = float(w[r]);
    if (!p.normals.empty()) {
      float* nn = &p.normals[3 * i];
      double v[3];
      for (int r = 0; r < 3; ++r) v[r] = nm[r][0] * nn[0] + nm[r][1] * nn[1] + nm[r][2] * nn[2];
      normalize3(v, nn);
    }
    if (!p.tangents.empty()) {
      float* t = &p.tangents[4 * i];
      double v[3];
      for (int r = 0; r < 3; ++r) v[r] = L(r, 0) * t[0] + L(r, 1) * t[1] + L(r, 2) * t[2];
      normalize3(v, t);
      if (det < 0) t[3] = -t[3];
    }
  }
  if (det < 0)  // a mirroring transform turns counter-clockwise triangles clockwise
    for (std::size_t t = 0; t + 2 < p.indices.size(); t += 3) std::swap(p.indices[t + 1], p.indices[t + 2]);
  for (float v : p.positions)
    if (!std::isfinite(v)) return false;
  return true;
}

void Walk::primitive(std::size_t mesh, std::size_t pi, std::size_t nodeIndex, const Mat4& world) {
  const tinygltf::Primitive& prim = model.meshes[mesh].primitives[pi];
  const std::string where = at("meshes", mesh) + ".primitives[" + std::to_string(pi) + "]";
  const int mode = prim.mode < 0 ? TINYGLTF_MODE_TRIANGLES : prim.mode;
  if (mode <= TINYGLTF_MODE_LINE_STRIP) {
    ++skippedLines;
    return;
  }
  if (mode > TINYGLTF_MODE_TRIANGLE_FAN)
    doc.fail(where + ".mode", "unknown primitive mode " + std::to_string(mode) + "; expected 0 to 6");
  if (!prim.targets.empty()) morphs = true;
  if (prim.material >= 0 && std::size_t(prim.material) >= asset.materials.size())
    doc.fail(where + ".material", "material " + std::to_string(prim.material) + " does not exist (the file has " +
                                      std::to_string(asset.materials.size()) + "); re-export the file");
  Primitive p = assemble(prim, where, mode);
  p.material = doc.variantMaterial(mesh, pi, variant, prim.material);
  p.where = where + " (node " + std::to_string(nodeIndex) + ")";
  if (p.tangents.empty() && p.material >= 0) {
    const Material& m = asset.materials[std::size_t(p.material)];
    const int uvSet = tangentUvSet(m);
    if (m.needsTangents() && !(uvSet == 1 ? p.uv1 : p.uv0).empty()) {
      const std::size_t before = p.vertexCount();
      generateTangents(p, uvSet);
      take(p.vertexCount() - before, where);  // mirrored vertices were split
    }
  }
  if (!toWorld(p, world)) return;
  asset.primitives.push_back(std::move(p));
}

void Walk::node(std::size_t i, const Mat4& world) {
  const tinygltf::Node& n = model.nodes[i];
  if (n.mesh >= 0) {
    if (std::size_t(n.mesh) >= model.meshes.size())
      doc.fail(at("nodes", i) + ".mesh", "mesh " + std::to_string(n.mesh) + " does not exist (the file has " +
                                             std::to_string(model.meshes.size()) + "); re-export the file");
    if (n.skin >= 0) skins = true;
    for (std::size_t p = 0; p < model.meshes[std::size_t(n.mesh)].primitives.size(); ++p)
      primitive(std::size_t(n.mesh), p, i, world);
  }
  if (n.camera >= 0) {
    if (std::size_t(n.camera) >= model.cameras.size())
      doc.fail(at("nodes", i) + ".camera", "camera " + std::to_string(n.camera) + " does not exist (the file has " +
                                               std::to_string(model.cameras.size()) + "); re-export the file");
    Camera c = doc.camera(n.camera);
    c.node = int(i);
    c.world = world;
    asset.cameras.push_back(c);
  }
  if (auto light = doc.nodeLight(i)) {
    for (int r = 0; r < 3; ++r) light->position[std::size_t(r)] = float(world[12 + r]);
    double d[3], len = 0;
    for (int r = 0; r < 3; ++r) {
      d[r] = -world[8 + r];  // world -Z: minus the third column
      len += d[r] * d[r];
    }
    len = std::sqrt(len);
    if (len > 0 && std::isfinite(len))
      for (int r = 0; r < 3; ++r) light->direction[std::size_t(r)] = float(d[r] / len);
    asset.lights.push_back(*light);
  }
}

int chooseScene(const tinygltf::Model& model, const Document& doc, const LoadOptions& options) {
  const std::size_t count = model.scenes.size();
  if (options.scene >= 0) {
    if (std::size_t(options.scene) >= count)
      throw Error(doc.source() + ": scene " + std::to_string(options.scene) + " is out of range: the file has " +
                  std::to_string(count) + " scene" + (count == 1 ? "" : "s"));
    return options.scene;
  }
  if (model.defaultScene >= 0) {
    if (std::size_t(model.defaultScene) >= count)
      doc.fail("scene", "scene " + std::to_string(model.defaultScene) + " does not exist (the file has " +
                            std::to_string(count) + "); re-export the file");
    return model.defaultScene;
  }
  return count ? 0 : -1;
}

int chooseVariant(const Asset& asset, const LoadOptions& options, const Document& doc) {
  if (options.variant.empty()) return -1;
  const auto it = std::find(asset.variants.begin(), asset.variants.end(), options.variant);
  if (it != asset.variants.end()) return int(it - asset.variants.begin());
  std::string names;
  for (const auto& v : asset.variants) names += (names.empty() ? "" : ", ") + brdfcl::detail::printable(v, 80);
  throw Error(doc.source() + ": " +
              optionWithValue("--variant", "'" + brdfcl::detail::printable(options.variant, 80) + "'") + " is not a variant of this file; " +
              (names.empty() ? "it has none" : "it has: " + names));
}

void computeBounds(Asset& asset) {
  bool any = false;
  for (const Primitive& p : asset.primitives)
    for (std::uint32_t i : p.indices)
      for (int k = 0; k < 3; ++k) {
        const double v = p.positions[3 * i + std::size_t(k)];
        if (!any || v < asset.boundsMin[std::size_t(k)]) asset.boundsMin[std::size_t(k)] = v;
        if (!any || v > asset.boundsMax[std::size_t(k)]) asset.boundsMax[std::size_t(k)] = v;
        if (k == 2) any = true;
      }
}

}  // namespace

void buildScene(const tinygltf::Model& model, const Document& doc, const LoadOptions& options, Asset& asset) {
  Walk walk{model, doc, options, asset};
  walk.variant = chooseVariant(asset, options, doc);
  const std::vector<int> parent = checkGraph(model, doc);
  const int s = chooseScene(model, doc, options);
  if (s >= 0) {
    const std::string sp = at("scenes", std::size_t(s)) + ".nodes";
    std::vector<bool> root(model.nodes.size(), false);
    std::vector<std::pair<std::size_t, Mat4>> stack;
    const std::vector<int>& roots = model.scenes[std::size_t(s)].nodes;
    for (auto it = roots.rbegin(); it != roots.rend(); ++it) {
      const int r = *it;
      if (r < 0 || std::size_t(r) >= model.nodes.size())
        doc.fail(sp, "node " + std::to_string(r) + " does not exist (the file has " + std::to_string(model.nodes.size()) + ")");
      if (parent[std::size_t(r)] >= 0)
        doc.fail(sp, "nodes[" + std::to_string(r) + "] is a root of the scene but also a child of nodes[" +
                         std::to_string(parent[std::size_t(r)]) + "]; re-export the file");
      if (root[std::size_t(r)]) doc.fail(sp, "nodes[" + std::to_string(r) + "] is listed twice; re-export the file");
      root[std::size_t(r)] = true;
      stack.emplace_back(std::size_t(r), identity());
    }
    // Depth first without recursion: a chain of many nodes must not exhaust the stack.
    while (!stack.empty()) {
      const auto [i, parentWorld] = stack.back();
      stack.pop_back();
      const Mat4 world = multiply(parentWorld, localMatrix(model.nodes[i], i, doc));
      if (!finite(world)) doc.fail(at("nodes", i), "the world transform overflows; fix the node's transform");
      walk.node(i, world);
      const std::vector<int>& children = model.nodes[i].children;
      for (auto it = children.rbegin(); it != children.rend(); ++it) stack.emplace_back(std::size_t(*it), world);
    }
  }
  const std::string& src = doc.source();
  if (walk.skippedLines)
    asset.warnings.push_back(src + ": " + std::to_string(walk.skippedLines) +
                             " point or line primitive(s) skipped: brdfcl renders triangles only");
  if (walk.skins) asset.warnings.push_back(src + ": skins are ignored: skinned meshes are rendered in their rest pose");
  if (walk.morphs) asset.warnings.push_back(src + ": morph targets are ignored: meshes are rendered without them");
  computeBounds(asset);
}

}  // namespace brdfcl::gltf::detail
