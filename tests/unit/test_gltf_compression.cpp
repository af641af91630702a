// Tests of compressed glTF meshes: EXT_meshopt_compression (GltfMeshopt*) and
// KHR_draco_mesh_compression (GltfDraco*). The files are written with libmeshoptimizer's and
// Draco's own encoders through gltf_builder.hpp and must load to the mesh they were made from:
// bit for bit when lossless, within the quantization otherwise.
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

Grid grid() {
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
std::string bytesOf(const std::vector<T>& v) {
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
GltfBuilder plain(const Grid& g) {
  GltfBuilder b;
  b.addMeshNode(b.addTriangles(g.p, g.i, -1, g.n, g.uv));
  b.addScene({0});
  return b;
}

// The grid with every view compressed losslessly (no filters); indices by `indexMode`, 16-bit
// when `shortIndices`.
GltfBuilder compressed(const Grid& g, Fallback f, const std::string& indexMode = "TRIANGLES", bool shortIndices = false) {
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
std::vector<std::uint32_t> canonical(std::vector<std::uint32_t> i) {
  for (std::size_t t = 0; t + 2 < i.size(); t += 3)
    while (i[t] > i[t + 1] || i[t] > i[t + 2]) std::rotate(i.begin() + long(t), i.begin() + long(t) + 1, i.begin() + long(t) + 3);
  return i;
}

void expectSame(const gltf::Primitive& a, const gltf::Primitive& b) {
  EXPECT_EQ(a.positions, b.positions);
  EXPECT_EQ(a.normals, b.normals);
  EXPECT_EQ(a.uv0, b.uv0);
  EXPECT_EQ(canonical(a.indices), canonical(b.indices));
  EXPECT_EQ(a.indices.size(), b.indices.size());
}

TEST_F(GltfMeshopt, LosslessViewsLoadAsTheUncompressedMesh) {
  const Grid g = grid();
  const gltf::Primitive ref = load(plain(g));
  ASSERT_EQ(ref.vertexCount(), g.vertices());
  ASSERT_EQ(ref.indices, g.i);
  for (Storage s : {Storage::DataUris, Storage::Glb, Storage::ExternalFiles}) {
    SCOPED_TRACE(int(s));
    expectSame(load(compressed(g, Fallback::Dataless), s), ref);
    expectSame(load(compressed(g, Fallback::WithData), s), ref);
  }
  expectSame(load(compressed(g, Fallback::Dataless, "INDICES")), ref);
  expectSame(load(compressed(g, Fallback::Dataless, "TRIANGLES", true)), ref);
  expectSame(load(compressed(g, Fallback::WithData, "INDICES", true), Storage::Glb), ref);
}

TEST_F(GltfMeshopt, RequiredWithoutCompressedViewsIsNotRefused) {
  GltfBuilder b = plain(grid());
  b.useExtension("EXT_meshopt_compression", true);
  const gltf::Asset a = gltf::load(b.write(scratch.dir(), "m.gltf"));
  EXPECT_EQ(a.primitives.size(), 1u);
  EXPECT_TRUE(a.warnings.empty());
}

TEST_F(GltfMeshopt, FiltersLoadWithinTheirQuantization) {
  const Grid g = grid();
  const std::size_t n = g.vertices();
  // OCTAHEDRAL: normals as 8-bit (stride 4) and 16-bit (stride 8) normalized integers.
  std::vector<float> n4;
  for (std::size_t k = 0; k < n; ++k) n4.insert(n4.end(), {g.n[3 * k], g.n[3 * k + 1], g.n[3 * k + 2], 0.0f});
  for (int stride : {4, 8}) {
    SCOPED_TRACE(stride);
    GltfBuilder b;
    {
      MeshoptWriter w(b, Fallback::Dataless);
      b.useExtension("KHR_mesh_quantization", true);
      std::string oct(n * std::size_t(stride), '\0');
      meshopt_encodeFilterOct(oct.data(), n, std::size_t(stride), stride == 4 ? 8 : 16, n4.data());
      std::string decoded = oct;
      meshopt_decodeFilterOct(decoded.data(), n, std::size_t(stride));
      // EXPONENTIAL: positions with a 15-bit mantissa.
      std::string exp(n * 12, '\0');
      meshopt_encodeFilterExp(exp.data(), n, 12, 15, g.p.data());
      std::string expDecoded = exp;
      meshopt_decodeFilterExp(expDecoded.data(), n, 12);
      const int pos = w.accessor(w.view(expDecoded, n, 12, "ATTRIBUTES", "EXPONENTIAL", exp), 5126, n, "VEC3");
      const int nrm = w.accessor(w.view(decoded, n, std::size_t(stride), "ATTRIBUTES", "OCTAHEDRAL", oct),
                                 stride == 4 ? 5120 : 5122, n, "VEC3", true);
      const int ind = w.accessor(w.view(bytesOf(g.i), g.i.size(), 4, "TRIANGLES"), 5125, g.i.size(), "SCALAR");
      b.addMesh({GltfBuilder::primitive({{"POSITION", pos}, {"NORMAL", nrm}}, ind)});
    }
    b.addMeshNode(0);
    b.addScene({0});
    const gltf::Primitive p = load(b);
    ASSERT_EQ(p.positions.size(), g.p.size());
    ASSERT_EQ(p.normals.size(), g.n.size());
    EXPECT_EQ(canonical(p.indices), canonical(g.i));
    const float normalTolerance = stride == 4 ? 0.02f : 1e-4f;
    for (std::size_t k = 0; k < g.p.size(); ++k) {
      EXPECT_NEAR(p.positions[k], g.p[k], 1e-4f) << k;
      EXPECT_NEAR(p.normals[k], g.n[k], normalTolerance) << k;
    }
  }
}

// The decoder's guard against huge claims relies on no bitstream expanding more than 64x.
TEST_F(GltfMeshopt, EncoderNeverExpandsMoreThan64Times) {
  for (std::size_t stride : {4u, 16u, 256u}) {
    const std::size_t count = 100000;
    const std::vector<unsigned char> zeros(count * stride, 0);
    std::vector<unsigned char> out(meshopt_encodeVertexBufferBound(count, stride));
    const std::size_t size = meshopt_encodeVertexBuffer(out.data(), out.size(), zeros.data(), count, stride);
    EXPECT_LE(count * stride, 64 * size) << stride;
  }
  const std::vector<unsigned int> same(300000, 0u);
  std::vector<unsigned char> out(meshopt_encodeIndexBufferBound(same.size(), 1));
  EXPECT_LE(same.size() * 4, 64 * meshopt_encodeIndexBuffer(out.data(), out.size(), same.data(), same.size()));
  out.assign(meshopt_encodeIndexSequenceBound(same.size(), 1), 0);
  EXPECT_LE(same.size() * 4, 64 * meshopt_encodeIndexSequence(out.data(), out.size(), same.data(), same.size()));
}

TEST_F(GltfMeshopt, CorruptDataIsAOneLineError) {
  const Grid g = grid();
  {
    GltfBuilder b = compressed(g, Fallback::Dataless);
    const std::size_t at = b.doc["bufferViews"][1]["extensions"]["EXT_meshopt_compression"]["byteOffset"];
    b.bin[at] = char(0x55);  // not a version header
    EXPECT_EQ(loadError(b), path(Storage::DataUris) +
                                ": bufferViews[1]: EXT_meshopt_compression data does not decode (meshopt error -1); re-export the file");
  }
  {
    GltfBuilder b = compressed(g, Fallback::WithData);
    json& ext = b.doc["bufferViews"][3]["extensions"]["EXT_meshopt_compression"];
    ext["byteLength"] = ext["byteLength"].get<int>() - 17;  // cut short
    EXPECT_EQ(loadError(b, Storage::Glb), path(Storage::Glb) +
                                              ": bufferViews[3]: EXT_meshopt_compression data does not decode (meshopt error -2); re-export the file");
  }
}

TEST_F(GltfMeshopt, HugeCountsAreRefusedBeforeAllocating) {
  const Grid g = grid();
  {
    GltfBuilder b = compressed(g, Fallback::Dataless);
    b.doc["bufferViews"][0]["extensions"]["EXT_meshopt_compression"]["count"] = 100000000;
    b.extraBuffers.clear();
    b.extraBuffers.push_back({{"byteLength", 4000000000u}, {"extensions", {{"EXT_meshopt_compression", {{"fallback", true}}}}}});
    const std::size_t len = b.doc["bufferViews"][0]["extensions"]["EXT_meshopt_compression"]["byteLength"];
    EXPECT_EQ(loadError(b), path(Storage::DataUris) + ": bufferViews[0].extensions.EXT_meshopt_compression: 100000000 elements of 12 bytes cannot come from " +
                                std::to_string(len) + " compressed bytes; the file is corrupt: re-export it");
    b.doc["bufferViews"][0]["extensions"]["EXT_meshopt_compression"]["count"] = 1ull << 40;
    EXPECT_EQ(loadError(b), path(Storage::DataUris) + ": bufferViews[0].extensions.EXT_meshopt_compression.count: 1099511627776 is more than brdfcl's limit of 268435456; re-export the file");
  }
}

TEST_F(GltfMeshopt, MalformedExtensionsAreOneLineErrors) {
  const Grid g = grid();
  const std::string p = path(Storage::DataUris);
  auto where = [&](int view) { return p + ": bufferViews[" + std::to_string(view) + "].extensions.EXT_meshopt_compression"; };
  // bufferViews: 0 positions (stride 12), 1 normals, 2 UVs (stride 8), 3 indices (TRIANGLES).
  auto edited = [&](int view, const std::function<void(json&)>& edit) {
    GltfBuilder b = compressed(g, Fallback::Dataless);
    edit(b.doc["bufferViews"][std::size_t(view)]["extensions"]["EXT_meshopt_compression"]);
    return loadError(b);
  };
  EXPECT_EQ(edited(2, [](json& x) { x["mode"] = "STRIPS"; }),
            where(2) + ".mode: expected \"ATTRIBUTES\", \"TRIANGLES\" or \"INDICES\", got string \"STRIPS\"");
  EXPECT_EQ(edited(2, [](json& x) { x.erase("mode"); }), where(2) + ": missing \"mode\"; re-export the file");
  EXPECT_EQ(edited(2, [](json& x) { x["count"] = -1; }), where(2) + ".count: expected an integer >= 0, got -1");
  EXPECT_EQ(edited(2, [](json& x) { x["count"] = 0; }), where(2) + ".count: expected at least 1, got 0; re-export the file");
  EXPECT_EQ(edited(2, [](json& x) { x["byteStride"] = 6; }),
            where(2) + ".byteStride: expected a multiple of 4 from 4 to 256 for mode ATTRIBUTES, got 6; re-export the file");
  EXPECT_EQ(edited(0, [](json& x) { x["filter"] = "QUATERNION"; }),
            where(0) + ".byteStride: expected 8 for filter QUATERNION, got 12; re-export the file");
  EXPECT_EQ(edited(0, [](json& x) { x["filter"] = "OCTAHEDRAL"; }),
            where(0) + ".byteStride: expected 4 or 8 for filter OCTAHEDRAL, got 12; re-export the file");
  EXPECT_EQ(edited(0, [](json& x) { x["filter"] = "SPLINE"; }),
            where(0) + ".filter: expected \"NONE\", \"OCTAHEDRAL\", \"QUATERNION\" or \"EXPONENTIAL\", got string \"SPLINE\"");
  EXPECT_EQ(edited(3, [](json& x) { x["filter"] = "EXPONENTIAL"; }),
            where(3) + ".filter: filter EXPONENTIAL needs mode ATTRIBUTES, not TRIANGLES; re-export the file");
  EXPECT_EQ(edited(3, [](json& x) { x["byteStride"] = 1; }),
            where(3) + ".byteStride: expected 2 or 4 for mode TRIANGLES, got 1; re-export the file");
  EXPECT_EQ(edited(3, [](json& x) { x["count"] = 10; }),
            where(3) + ".count: expected a multiple of 3 for mode TRIANGLES, got 10; re-export the file");
  EXPECT_EQ(edited(2, [](json& x) { x["buffer"] = 1; }),
            where(2) + ".buffer: buffers[1] is a fallback without data; the compressed data must be in a buffer that has it");
  EXPECT_EQ(edited(2, [](json& x) { x["buffer"] = 7; }), where(2) + ".buffer: buffer 7 does not exist (the file has 2); re-export the file");
  EXPECT_CONTAINS(edited(2, [](json& x) { x["byteOffset"] = 1000000; }), where(2) + ": bytes 1000000 + ");
  {
    GltfBuilder b = compressed(g, Fallback::Dataless);
    b.doc["bufferViews"][1].erase("extensions");
    EXPECT_EQ(loadError(b), p + ": bufferViews[1]: buffers[1] is an EXT_meshopt_compression fallback without data, but this view is not compressed; re-export the file");
  }
  {
    // tinygltf would read an image from the fallback buffer's (absent) bytes.
    GltfBuilder b = compressed(g, Fallback::Dataless);
    b.doc["images"] = json::array({{{"bufferView", 2}, {"mimeType", "image/png"}}});
    b.doc["textures"] = json::array({{{"source", 0}}});
    EXPECT_EQ(loadError(b, Storage::Glb), path(Storage::Glb) + ": images[0].bufferView: bufferViews[2] lies in an EXT_meshopt_compression fallback buffer, which has no data; brdfcl reads images from uncompressed views only: re-export the file");
  }
  {
    GltfBuilder b = compressed(g, Fallback::Dataless);
    b.extraBuffers[0]["extensions"]["EXT_meshopt_compression"]["fallback"] = "yes";
    EXPECT_EQ(loadError(b), p + ": buffers[1].extensions.EXT_meshopt_compression.fallback: expected true or false, got string \"yes\"");
  }
}

// --- KHR_draco_mesh_compression -----------------------------------------------------------------

struct DracoIds {
  int position = -1, normal = -1, uv = -1;
};

// The grid as a Draco mesh (a triangle soup, its equal corners merged into points).
std::unique_ptr<draco::Mesh> dracoGrid(const Grid& g, DracoIds& ids) {
  draco::TriangleSoupMeshBuilder mb;
  const int faces = int(g.i.size() / 3);
  mb.Start(faces);
  const int pa = mb.AddAttribute(draco::GeometryAttribute::POSITION, 3, draco::DT_FLOAT32);
  const int na = mb.AddAttribute(draco::GeometryAttribute::NORMAL, 3, draco::DT_FLOAT32);
  const int ta = mb.AddAttribute(draco::GeometryAttribute::TEX_COORD, 2, draco::DT_FLOAT32);
  for (int f = 0; f < faces; ++f) {
    const std::uint32_t* c = &g.i[std::size_t(f) * 3];
    mb.SetAttributeValuesForFace(pa, draco::FaceIndex(std::uint32_t(f)), &g.p[3 * c[0]], &g.p[3 * c[1]], &g.p[3 * c[2]]);
    mb.SetAttributeValuesForFace(na, draco::FaceIndex(std::uint32_t(f)), &g.n[3 * c[0]], &g.n[3 * c[1]], &g.n[3 * c[2]]);
    mb.SetAttributeValuesForFace(ta, draco::FaceIndex(std::uint32_t(f)), &g.uv[2 * c[0]], &g.uv[2 * c[1]], &g.uv[2 * c[2]]);
  }
  std::unique_ptr<draco::Mesh> mesh = mb.Finalize();
  if (!mesh) return mesh;
  auto id = [&](draco::GeometryAttribute::Type t) { return int(mesh->attribute(mesh->GetNamedAttributeId(t))->unique_id()); };
  ids = {id(draco::GeometryAttribute::POSITION), id(draco::GeometryAttribute::NORMAL), id(draco::GeometryAttribute::TEX_COORD)};
  return mesh;
}

std::string dracoEncode(const draco::Mesh& mesh, int method, bool quantize) {
  draco::Encoder enc;
  enc.SetEncodingMethod(method);
  if (quantize) {
    enc.SetAttributeQuantization(draco::GeometryAttribute::POSITION, 14);
    enc.SetAttributeQuantization(draco::GeometryAttribute::NORMAL, 10);
    enc.SetAttributeQuantization(draco::GeometryAttribute::TEX_COORD, 12);
  }
  draco::EncoderBuffer out;
  const draco::Status st = enc.EncodeMeshToBuffer(mesh, &out);
  EXPECT_TRUE(st.ok()) << st.error_msg_string();
  return std::string(out.data(), out.size());
}

// The grid in a file whose one primitive is Draco-compressed: required (accessors without
// bufferViews) or only used (accessors keep the uncompressed data as their fallback).
GltfBuilder dracoFile(const Grid& g, int method, bool quantize, bool required) {
  DracoIds ids;
  const std::unique_ptr<draco::Mesh> mesh = dracoGrid(g, ids);
  EXPECT_TRUE(mesh);
  const std::string data = mesh ? dracoEncode(*mesh, method, quantize) : std::string();
  GltfBuilder b;
  b.useExtension("KHR_draco_mesh_compression", required);
  const int view = b.addBufferView(data.data(), data.size());
  std::map<std::string, int> attrs;
  int indices = -1;
  if (required) {
    auto accessor = [&](int componentType, std::size_t count, const char* type) {
      b.doc["accessors"].push_back({{"componentType", componentType}, {"count", count}, {"type", type}});
      return int(b.doc["accessors"].size()) - 1;
    };
    const std::size_t points = mesh ? mesh->num_points() : 0;
    attrs = {{"POSITION", accessor(5126, points, "VEC3")}, {"NORMAL", accessor(5126, points, "VEC3")},
             {"TEXCOORD_0", accessor(5126, points, "VEC2")}};
    indices = accessor(5125, g.i.size(), "SCALAR");
  } else {
    attrs = {{"POSITION", b.addFloats(g.p, "VEC3")}, {"NORMAL", b.addFloats(g.n, "VEC3")}, {"TEXCOORD_0", b.addFloats(g.uv, "VEC2")}};
    indices = b.addIndices(g.i);
  }
  json prim = GltfBuilder::primitive(attrs, indices);
  prim["extensions"]["KHR_draco_mesh_compression"] = {
      {"bufferView", view}, {"attributes", {{"POSITION", ids.position}, {"NORMAL", ids.normal}, {"TEXCOORD_0", ids.uv}}}};
  b.addMeshNode(b.addMesh({prim}));
  b.addScene({0});
  return b;
}

// Every loaded triangle matches one of the reference's (corners rotated, winding kept) within the
// tolerances, each reference triangle once: Draco may renumber points and reorder faces.
void expectSameTriangles(const gltf::Primitive& p, const gltf::Primitive& ref, float tolP, float tolN, float tolUv) {
  ASSERT_EQ(p.indices.size(), ref.indices.size());
  ASSERT_EQ(p.normals.size(), p.positions.size());
  ASSERT_EQ(p.uv0.size() / 2, p.positions.size() / 3);
  auto near = [](const float* a, const float* b, int n, float tol) {
    for (int k = 0; k < n; ++k)
      if (std::fabs(a[k] - b[k]) > tol) return false;
    return true;
  };
  std::vector<bool> used(ref.indices.size() / 3, false);
  for (std::size_t t = 0; t < p.indices.size(); t += 3) {
    bool found = false;
    for (std::size_t s = 0; s < used.size() && !found; ++s) {
      if (used[s]) continue;
      for (int r = 0; r < 3 && !found; ++r) {
        bool all = true;
        for (int c = 0; c < 3 && all; ++c) {
          const std::uint32_t a = p.indices[t + std::size_t(c)], b = ref.indices[3 * s + std::size_t((c + r) % 3)];
          all = near(&p.positions[3 * a], &ref.positions[3 * b], 3, tolP) &&
                near(&p.normals[3 * a], &ref.normals[3 * b], 3, tolN) && near(&p.uv0[2 * a], &ref.uv0[2 * b], 2, tolUv);
        }
        if (all) found = used[s] = true;
      }
    }
    EXPECT_TRUE(found) << "loaded triangle " << t / 3 << " matches no reference triangle";
  }
}

class GltfDraco : public GltfMeshopt {};

// libdraco.a carries its own copy of tinygltf (another version): linked before libtinygltf.so,
// its objects would replace Debian's tinygltf in the loader and corrupt the heap.
TEST_F(GltfDraco, TinygltfComesFromDebiansLibrary) {
  Dl_info info{};
  ASSERT_NE(dladdr(reinterpret_cast<void*>(&tinygltf::DecodeDataURI), &info), 0);
  ASSERT_NE(info.dli_fname, nullptr);
  EXPECT_NE(std::string(info.dli_fname).find("libtinygltf"), std::string::npos) << info.dli_fname;
}

TEST_F(GltfDraco, LosslessMeshLoadsAsTheUncompressedMesh) {
  const Grid g = grid();
  const gltf::Primitive ref = load(plain(g));
  for (int method : {draco::MESH_SEQUENTIAL_ENCODING, draco::MESH_EDGEBREAKER_ENCODING}) {
    SCOPED_TRACE(method);
    expectSameTriangles(load(dracoFile(g, method, false, true)), ref, 0.0f, 0.0f, 0.0f);
    expectSameTriangles(load(dracoFile(g, method, false, false), Storage::Glb), ref, 0.0f, 0.0f, 0.0f);
  }
}

TEST_F(GltfDraco, QuantizedMeshLoadsWithinTheQuantization) {
  const Grid g = grid();
  const gltf::Primitive ref = load(plain(g));
  for (int method : {draco::MESH_SEQUENTIAL_ENCODING, draco::MESH_EDGEBREAKER_ENCODING}) {
    SCOPED_TRACE(method);
    const gltf::Primitive p = load(dracoFile(g, method, true, true));
    expectSameTriangles(p, ref, 2e-4f, 0.01f, 5e-4f);
    // Quantized: not bit-identical, so the tolerances above are what the test checks.
    bool exact = true;
    for (std::size_t k = 0; k < p.positions.size() && k < ref.positions.size(); ++k) exact = exact && p.positions[k] == ref.positions[k];
    EXPECT_FALSE(exact && p.positions.size() == ref.positions.size() && p.indices == ref.indices);
  }
}

// Integer Draco values are normalized as the glTF accessor says (here UNSIGNED_SHORT UVs).
TEST_F(GltfDraco, IntegerAttributesFollowTheAccessorsNormalization) {
  const Grid g = grid();
  draco::TriangleSoupMeshBuilder mb;
  const int faces = int(g.i.size() / 3);
  mb.Start(faces);
  const int pa = mb.AddAttribute(draco::GeometryAttribute::POSITION, 3, draco::DT_FLOAT32);
  const int ta = mb.AddAttribute(draco::GeometryAttribute::TEX_COORD, 2, draco::DT_UINT16);
  std::vector<std::uint16_t> uv16;
  for (float u : g.uv) uv16.push_back(std::uint16_t(std::lround(u * 65535.0f)));
  for (int f = 0; f < faces; ++f) {
    const std::uint32_t* c = &g.i[std::size_t(f) * 3];
    mb.SetAttributeValuesForFace(pa, draco::FaceIndex(std::uint32_t(f)), &g.p[3 * c[0]], &g.p[3 * c[1]], &g.p[3 * c[2]]);
    mb.SetAttributeValuesForFace(ta, draco::FaceIndex(std::uint32_t(f)), &uv16[2 * c[0]], &uv16[2 * c[1]], &uv16[2 * c[2]]);
  }
  const std::unique_ptr<draco::Mesh> mesh = mb.Finalize();
  ASSERT_TRUE(mesh);
  const std::string data = dracoEncode(*mesh, draco::MESH_SEQUENTIAL_ENCODING, false);
  auto id = [&](draco::GeometryAttribute::Type t) { return int(mesh->attribute(mesh->GetNamedAttributeId(t))->unique_id()); };
  for (bool normalized : {true, false}) {
    GltfBuilder b;
    b.useExtension("KHR_draco_mesh_compression", true);
    b.useExtension("KHR_mesh_quantization", true);
    const int view = b.addBufferView(data.data(), data.size());
    b.doc["accessors"] = json::array({{{"componentType", 5126}, {"count", mesh->num_points()}, {"type", "VEC3"}},
                                      {{"componentType", 5123}, {"normalized", normalized}, {"count", mesh->num_points()}, {"type", "VEC2"}}});
    json prim = GltfBuilder::primitive({{"POSITION", 0}, {"TEXCOORD_0", 1}});
    prim["extensions"]["KHR_draco_mesh_compression"] = {
        {"bufferView", view}, {"attributes", {{"POSITION", id(draco::GeometryAttribute::POSITION)}, {"TEXCOORD_0", id(draco::GeometryAttribute::TEX_COORD)}}}};
    b.addMeshNode(b.addMesh({prim}));
    b.addScene({0});
    const gltf::Primitive p = load(b);
    ASSERT_EQ(p.indices.size(), g.i.size());  // indices made although the primitive had none
    ASSERT_EQ(p.uv0.size(), p.positions.size() / 3 * 2);
    for (std::size_t v = 0; v < p.positions.size() / 3; ++v) {
      // The grid's UV is (x, 1 - y) of its position.
      const double u = normalized ? double(std::lround(p.positions[3 * v] * 65535.0f)) / 65535.0 : std::lround(p.positions[3 * v] * 65535.0f);
      EXPECT_NEAR(p.uv0[2 * v], u, normalized ? 1e-6 : 0.0) << v;
    }
  }
}

TEST_F(GltfDraco, CorruptOrMismatchedDataIsAOneLineError) {
  const Grid g = grid();
  const std::string prim = path(Storage::DataUris) + ": meshes[0].primitives[0]";
  {
    GltfBuilder b = dracoFile(g, draco::MESH_EDGEBREAKER_ENCODING, true, true);
    b.doc["bufferViews"][0]["byteLength"] = 12;  // cut short
    const std::string e = loadError(b);
    EXPECT_CONTAINS(e, prim + ": KHR_draco_mesh_compression data does not decode (");
    EXPECT_CONTAINS(e, "); re-export the file");
    EXPECT_EQ(e.find('\n'), std::string::npos);
  }
  {
    GltfBuilder b = dracoFile(g, draco::MESH_SEQUENTIAL_ENCODING, false, true);
    b.doc["meshes"][0]["primitives"][0]["extensions"]["KHR_draco_mesh_compression"]["attributes"]["NORMAL"] = 9;
    EXPECT_EQ(loadError(b), prim + ".extensions.KHR_draco_mesh_compression.attributes.NORMAL: Draco attribute 9 is not in the compressed data; re-export the file");
  }
  {
    GltfBuilder b = dracoFile(g, draco::MESH_SEQUENTIAL_ENCODING, false, true);
    b.doc["meshes"][0]["primitives"][0]["extensions"]["KHR_draco_mesh_compression"]["attributes"]["TEXCOORD_1"] = 2;
    EXPECT_EQ(loadError(b), prim + ".extensions.KHR_draco_mesh_compression.attributes.TEXCOORD_1: the primitive has no attribute TEXCOORD_1; re-export the file");
  }
  {
    GltfBuilder b = dracoFile(g, draco::MESH_SEQUENTIAL_ENCODING, false, true);
    b.doc["meshes"][0]["primitives"][0]["extensions"]["KHR_draco_mesh_compression"]["bufferView"] = 5;
    EXPECT_EQ(loadError(b), prim + ".extensions.KHR_draco_mesh_compression.bufferView: bufferView 5 does not exist (the file has 1); re-export the file");
  }
  {
    GltfBuilder b = dracoFile(g, draco::MESH_SEQUENTIAL_ENCODING, false, true);
    b.doc["accessors"][1]["type"] = "VEC4";
    EXPECT_EQ(loadError(b), prim + ".extensions.KHR_draco_mesh_compression.attributes.NORMAL: Draco attribute " +
                                std::to_string(b.doc["meshes"][0]["primitives"][0]["extensions"]["KHR_draco_mesh_compression"]["attributes"]["NORMAL"].get<int>()) +
                                " has 3 components, accessors[1] needs 4; re-export the file");
  }
}

// A face count of 2^32 - 16 written into a small stream: libdraco refuses it (without the 48 GB
// its faces would take), and the loader reports that on one line.
TEST_F(GltfDraco, HugeClaimedCountsAreRefused) {
  GltfBuilder b = dracoFile(grid(), draco::MESH_SEQUENTIAL_ENCODING, false, true);
  std::string data = b.bin.substr(0, b.doc["bufferViews"][0]["byteLength"].get<std::size_t>());
  // Draco 1.5's sequential layout: an 11-byte header ("DRACO", version, type, method, flags), then
  // the face count as a varint.
  ASSERT_EQ(data.substr(0, 5), "DRACO");
  ASSERT_EQ(std::uint8_t(data[11]), 40u);
  data = data.substr(0, 11) + std::string("\xf0\xff\xff\xff\x0f", 5) + data.substr(12);
  b.bin = data;
  b.doc["bufferViews"][0]["byteLength"] = data.size();
  EXPECT_EQ(loadError(b), path(Storage::DataUris) + ": meshes[0].primitives[0]: KHR_draco_mesh_compression data does not decode (Failed to decode geometry data.); re-export the file");
}

TEST_F(GltfDraco, MeshesBeyondTheElementLimitAreRefused) {
  const Grid g = grid();
  gltf::LoadOptions o;
  o.maxElements = 50;  // the grid has 30 points and 40 triangles
  EXPECT_EQ(loadError(dracoFile(g, draco::MESH_EDGEBREAKER_ENCODING, true, true), Storage::DataUris, o),
            path(Storage::DataUris) + ": meshes[0].primitives[0]: the Draco mesh has 30 points and 40 triangles, more than brdfcl's limit of 50; simplify the model");
}

}  // namespace
