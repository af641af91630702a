// What the compressed-mesh tests share (test_gltf_compression, test_gltf_draco): a curved grid
// mesh, a writer of meshopt-compressed views, the fixture and the reference comparisons.
#pragma once

#include <gtest/gtest.h>
#include <draco/compression/encode.h>
#include <draco/mesh/triangle_soup_mesh_builder.h>
#include <dlfcn.h>
#include <meshoptimizer.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "brdfcl/gltf.hpp"
#include "gltf_builder.hpp"
#include "process.hpp"
#include "support.hpp"

namespace tinygltf {
// Declared here (tiny_gltf.h needs stb's include path): a free function of Debian's libtinygltf.
bool DecodeDataURI(std::vector<unsigned char>* out, std::string& mime, const std::string& in, std::size_t reqBytes,
                   bool checkSize);
}  // namespace tinygltf

namespace gltf = brdfcl::gltf;
using brdfcl::test::errorOf;
using brdfcl::test::GltfBuilder;
using brdfcl::test::Storage;
using json = nlohmann::json;

namespace {

// A curved 6 x 5 grid: positions, unit normals, UVs and triangle indices.
struct Grid {
  std::vector<float> p, n, uv;
  std::vector<std::uint32_t> i;
  std::size_t vertices() const { return p.size() / 3; }
};

inline Grid grid() {
  Grid g;
  const int nx = 6, ny = 5;
  for (int y = 0; y < ny; ++y)
    for (int x = 0; x < nx; ++x) {
      const float u = float(x) / (nx - 1), v = float(y) / (ny - 1);
      const float z = 0.1f * std::sin(3.0f * u) * std::cos(2.0f * v);
      g.p.insert(g.p.end(), {u, v, z});
      const float dzdu = 0.3f * std::cos(3.0f * u) * std::cos(2.0f * v);
      const float dzdv = -0.2f * std::sin(3.0f * u) * std::sin(2.0f * v);
      const float len = std::sqrt(dzdu * dzdu + dzdv * dzdv + 1.0f);
      g.n.insert(g.n.end(), {-dzdu / len, -dzdv / len, 1.0f / len});
      g.uv.insert(g.uv.end(), {u, 1.0f - v});
    }
  for (int y = 0; y + 1 < ny; ++y)
    for (int x = 0; x + 1 < nx; ++x) {
      const std::uint32_t a = std::uint32_t(y * nx + x), b = a + 1, c = a + nx, d = c + 1;
      g.i.insert(g.i.end(), {a, b, d, a, d, c});
    }
  return g;
}

template <class T>
inline std::string bytesOf(const std::vector<T>& v) {
  return std::string(reinterpret_cast<const char*>(v.data()), v.size() * sizeof(T));
}

enum class Fallback {
  Dataless,  // extension required; views lie in a `fallback: true` buffer that has no data
  WithData,  // extension only used; views hold the uncompressed bytes as well
};

// Writes compressed views into a GltfBuilder: compressed bytes go to buffers[0], the views' own
// ranges to the fallback buffer (buffers[1], no data) or, uncompressed, to buffers[0].
class MeshoptWriter {
 public:
  MeshoptWriter(GltfBuilder& b, Fallback fallback) : b_(b), fallback_(fallback) {
    b_.useExtension("EXT_meshopt_compression", fallback == Fallback::Dataless);
  }
  ~MeshoptWriter() { finish(); }

  // A view of `count` elements of `stride` bytes compressed by mode (ATTRIBUTES, TRIANGLES,
  // INDICES); `raw` is what it decodes to (after `filter`, whose encoded form is `filtered`).
  int view(const std::string& raw, std::size_t count, std::size_t stride, const std::string& mode,
           const std::string& filter = "NONE", const std::string& filtered = "") {
    const std::string& input = filtered.empty() ? raw : filtered;
    std::vector<unsigned char> out;
    if (mode == "ATTRIBUTES") {
      out.resize(meshopt_encodeVertexBufferBound(count, stride));
      out.resize(meshopt_encodeVertexBuffer(out.data(), out.size(), input.data(), count, stride));
    } else {
      std::vector<unsigned int> idx(count);
      for (std::size_t k = 0; k < count; ++k) {
        if (stride == 2) {
          std::uint16_t v;
          std::memcpy(&v, input.data() + 2 * k, 2);
          idx[k] = v;
        } else {
          std::memcpy(&idx[k], input.data() + 4 * k, 4);
        }
      }
      if (mode == "TRIANGLES") {
        out.resize(meshopt_encodeIndexBufferBound(count, 1 << 16));
        out.resize(meshopt_encodeIndexBuffer(out.data(), out.size(), idx.data(), count));
      } else {
        out.resize(meshopt_encodeIndexSequenceBound(count, 1 << 16));
        out.resize(meshopt_encodeIndexSequence(out.data(), out.size(), idx.data(), count));
      }
    }
    const std::size_t at = b_.appendBytes(out.data(), out.size());
    json ext = {{"buffer", 0}, {"byteOffset", at}, {"byteLength", out.size()}, {"byteStride", stride},
                {"count", count}, {"mode", mode}};
    if (filter != "NONE") ext["filter"] = filter;
    json v;
    if (fallback_ == Fallback::Dataless) {
      v = {{"buffer", 1}, {"byteOffset", fallbackSize_}, {"byteLength", raw.size()}};
      fallbackSize_ += (raw.size() + 3) / 4 * 4;
    } else {
      v = {{"buffer", 0}, {"byteOffset", b_.appendBytes(raw.data(), raw.size())}, {"byteLength", raw.size()}};
    }
    if (mode == "ATTRIBUTES") v["byteStride"] = stride;
    v["extensions"]["EXT_meshopt_compression"] = ext;
    b_.doc["bufferViews"].push_back(v);
    return int(b_.doc["bufferViews"].size()) - 1;
  }

  int accessor(int view, int componentType, std::size_t count, const std::string& type, bool normalized = false) {
    json a = {{"bufferView", view}, {"componentType", componentType}, {"count", count}, {"type", type}};
    if (normalized) a["normalized"] = true;
    b_.doc["accessors"].push_back(a);
    return int(b_.doc["accessors"].size()) - 1;
  }

  void finish() {
    if (fallback_ == Fallback::Dataless && b_.extraBuffers.empty() && fallbackSize_ > 0)
      b_.extraBuffers.push_back({{"byteLength", fallbackSize_},
                                 {"extensions", {{"EXT_meshopt_compression", {{"fallback", true}}}}}});
  }

 private:
  GltfBuilder& b_;
  Fallback fallback_;
  std::size_t fallbackSize_ = 0;
};

class GltfMeshopt : public ::testing::Test {
 protected:
  brdfcl::test::ScratchDir scratch{"gltf-meshopt"};
  std::string path(Storage s) const { return scratch.path(s == Storage::Glb ? "m.glb" : "m.gltf"); }
  gltf::Primitive load(const GltfBuilder& b, Storage s = Storage::DataUris) {
    const gltf::Asset a = gltf::load(b.write(scratch.dir(), s == Storage::Glb ? "m.glb" : "m.gltf", s));
    EXPECT_EQ(a.primitives.size(), 1u);
    return a.primitives.empty() ? gltf::Primitive{} : a.primitives[0];
  }
  std::string loadError(const GltfBuilder& b, Storage s = Storage::DataUris, const gltf::LoadOptions& o = {}) {
    const std::string p = b.write(scratch.dir(), s == Storage::Glb ? "m.glb" : "m.gltf", s);
    return errorOf([&] { gltf::load(p, o); });
  }
};

// The grid uncompressed, as the reference.
inline GltfBuilder plain(const Grid& g) {
  GltfBuilder b;
  b.addMeshNode(b.addTriangles(g.p, g.i, -1, g.n, g.uv));
  b.addScene({0});
  return b;
}

// The grid with every view compressed losslessly (no filters); indices by `indexMode`, 16-bit
// when `shortIndices`.
inline GltfBuilder compressed(const Grid& g, Fallback f, const std::string& indexMode = "TRIANGLES", bool shortIndices = false) {
  GltfBuilder b;
  {
    MeshoptWriter w(b, f);
    const std::size_t n = g.vertices();
    const int pos = w.accessor(w.view(bytesOf(g.p), n, 12, "ATTRIBUTES"), 5126, n, "VEC3");
    const int nrm = w.accessor(w.view(bytesOf(g.n), n, 12, "ATTRIBUTES"), 5126, n, "VEC3");
    const int uv = w.accessor(w.view(bytesOf(g.uv), n, 8, "ATTRIBUTES"), 5126, n, "VEC2");
    std::string idx = bytesOf(g.i);
    if (shortIndices) idx = bytesOf(std::vector<std::uint16_t>(g.i.begin(), g.i.end()));
    const int ind = w.accessor(w.view(idx, g.i.size(), shortIndices ? 2 : 4, indexMode), shortIndices ? 5123 : 5125,
                               g.i.size(), "SCALAR");
    b.addMesh({GltfBuilder::primitive({{"POSITION", pos}, {"NORMAL", nrm}, {"TEXCOORD_0", uv}}, ind)});
  }
  b.addMeshNode(0);
  b.addScene({0});
  return b;
}

// Each triangle rotated to start at its smallest index: meshopt's TRIANGLES codec may rotate a
// triangle's corners (keeping its winding and the triangles' order).
inline std::vector<std::uint32_t> canonical(std::vector<std::uint32_t> i) {
  for (std::size_t t = 0; t + 2 < i.size(); t += 3)
    while (i[t] > i[t + 1] || i[t] > i[t + 2]) std::rotate(i.begin() + long(t), i.begin() + long(t) + 1, i.begin() + long(t) + 3);
  return i;
}

inline void expectSame(const gltf::Primitive& a, const gltf::Primitive& b) {
  EXPECT_EQ(a.positions, b.positions);
  EXPECT_EQ(a.normals, b.normals);
  EXPECT_EQ(a.uv0, b.uv0);
  EXPECT_EQ(canonical(a.indices), canonical(b.indices));
  EXPECT_EQ(a.indices.size(), b.indices.size());
}

}  // namespace
