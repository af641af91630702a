// Tests of the glTF loader (host/src/gltf): synthetic files from gltf_builder.hpp for every feature
// (storage kinds, transforms, strips and fans, accessor types, sparse, materials, images, cameras,
// lights, variants), tangent generation against analytic tangents, every error message, and the
// real sample assets (assets.hpp; skipped when absent).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <filesystem>
#include <functional>
#include <numeric>
#include <string>
#include <vector>

#include "assets.hpp"
#include "brdfcl/error.hpp"
#include "brdfcl/gltf.hpp"
#include "gltf_builder.hpp"
#include "host/src/gltf/tangents.hpp"
#include "process.hpp"
#include "support.hpp"

namespace gltf = brdfcl::gltf;
using brdfcl::test::errorOf;
using brdfcl::test::GltfBuilder;
using brdfcl::test::Storage;
using json = nlohmann::json;

namespace {

constexpr double kPi = 3.14159265358979323846;

class GltfTest : public ::testing::Test {
 protected:
  brdfcl::test::ScratchDir scratch{"gltf"};
  std::string write(const GltfBuilder& b, const std::string& name, Storage s = Storage::DataUris) {
    return b.write(scratch.dir(), name, s);
  }
  gltf::Asset load(const GltfBuilder& b, Storage s = Storage::DataUris, const gltf::LoadOptions& o = {}) {
    return gltf::load(write(b, s == Storage::Glb ? "m.glb" : "m.gltf", s), o);
  }
  std::string loadError(const GltfBuilder& b, Storage s = Storage::DataUris, const gltf::LoadOptions& o = {}) {
    const std::string p = write(b, s == Storage::Glb ? "m.glb" : "m.gltf", s);
    return errorOf([&] { gltf::load(p, o); });
  }
  std::string bytesError(const std::string& bytes, const std::string& name) {
    const std::string p = scratch.path(name);
    GltfBuilder::writeFile(p, bytes);
    return errorOf([&] { gltf::load(p); });
  }
};
class GltfLoader : public GltfTest {};
class GltfErrors : public GltfTest {};
class GltfTangents : public GltfTest {};

// A unit quad in z = 0, two triangles, normals +Z, UVs with v down.
const std::vector<float> kQuadP = {0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0};
const std::vector<float> kQuadN = {0, 0, 1, 0, 0, 1, 0, 0, 1, 0, 0, 1};
const std::vector<float> kQuadUv = {0, 1, 1, 1, 1, 0, 0, 0};
const std::vector<std::uint32_t> kQuadI = {0, 1, 2, 0, 2, 3};

GltfBuilder quad(json node = json::object(), int material = -1) {
  GltfBuilder b;
  const int mesh = b.addTriangles(kQuadP, kQuadI, material, kQuadN, kQuadUv);
  b.addScene({b.addMeshNode(mesh, node)});
  return b;
}

std::array<double, 3> vertex(const std::vector<float>& v, std::size_t i, std::size_t stride = 3) {
  return {v[stride * i], v[stride * i + 1], v[stride * i + 2]};
}

double angleDeg(std::array<double, 3> a, std::array<double, 3> b) {
  const double d = a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
  const double la = std::sqrt(a[0] * a[0] + a[1] * a[1] + a[2] * a[2]), lb = std::sqrt(b[0] * b[0] + b[1] * b[1] + b[2] * b[2]);
  return std::acos(std::max(-1.0, std::min(1.0, d / (la * lb)))) * 180.0 / kPi;
}

std::array<double, 3> crossD(std::array<double, 3> a, std::array<double, 3> b) {
  return {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]};
}

// ---------------------------------------------------------------------------------------------
// Geometry, storage and transforms

TEST_F(GltfLoader, QuadLoadsFromDataUrisExternalFilesAndGlb) {
  for (Storage s : {Storage::DataUris, Storage::ExternalFiles, Storage::Glb}) {
    const gltf::Asset a = load(quad(), s);
    ASSERT_EQ(a.primitives.size(), 1u);
    const gltf::Primitive& p = a.primitives[0];
    EXPECT_EQ(p.positions, kQuadP);
    EXPECT_EQ(p.normals, kQuadN);
    EXPECT_EQ(p.uv0, kQuadUv);
    EXPECT_EQ(p.indices, kQuadI);
    EXPECT_TRUE(p.tangents.empty());
    EXPECT_FALSE(p.generatedTangents);
    EXPECT_EQ(p.material, -1);
    EXPECT_EQ(p.where, "meshes[0].primitives[0] (node 0)");
    EXPECT_EQ(a.boundsMin, (std::array<double, 3>{0, 0, 0}));
    EXPECT_EQ(a.boundsMax, (std::array<double, 3>{1, 1, 0}));
    EXPECT_TRUE(a.warnings.empty());
  }
}

TEST_F(GltfLoader, TrsAndMatrixComposeDepthFirstInDoublePrecision) {
  GltfBuilder b;
  const int mesh = b.addTriangles(kQuadP, kQuadI, -1, kQuadN, kQuadUv);
  // Child: rotate 90 degrees about +Z, scale x by 2, then translate by (10, 0, 0); parent: matrix translate (0, 0, 5).
  const double s = std::sqrt(0.5);
  const int child = b.addMeshNode(mesh, {{"translation", {10, 0, 0}}, {"rotation", {0, 0, s, s}}, {"scale", {2, 1, 1}}});
  const int parent = b.addNode({{"children", {child}}, {"matrix", {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 5, 1}}});
  b.addScene({parent});
  const gltf::Asset a = load(b);
  ASSERT_EQ(a.primitives.size(), 1u);
  const auto& p = a.primitives[0];
  // Local (1, 1, 0) -> scale (2, 1, 0) -> rotate (-1, 2, 0) -> translate (9, 2, 0) -> parent (9, 2, 5).
  const auto v = vertex(p.positions, 2);
  EXPECT_NEAR(v[0], 9, 1e-6);
  EXPECT_NEAR(v[1], 2, 1e-6);
  EXPECT_NEAR(v[2], 5, 1e-6);
  EXPECT_NEAR(vertex(p.normals, 0)[2], 1, 1e-6);
  EXPECT_EQ(p.where, "meshes[0].primitives[0] (node 0)");
  EXPECT_NEAR(a.boundsMin[0], 9, 1e-6);
  EXPECT_NEAR(a.boundsMax[1], 2, 1e-6);
  EXPECT_NEAR(a.boundsMax[2], 5, 1e-6);
}

TEST_F(GltfLoader, NormalsUseTheInverseTransposeAndStayUnit) {
  GltfBuilder b;
  // A slanted normal (1, 1, 0)/sqrt2 under scale (2, 1, 1) becomes (1/2, 1, 0) normalized.
  const float r = float(std::sqrt(0.5));
  const int mesh = b.addTriangles({0, 0, 0, 1, -1, 0, 0, 0, 1}, {0, 1, 2}, -1, {r, r, 0, r, r, 0, r, r, 0});
  b.addScene({b.addMeshNode(mesh, {{"scale", {2, 1, 1}}})});
  const auto n = vertex(load(b).primitives[0].normals, 0);
  EXPECT_NEAR(n[0], 0.5 / std::sqrt(1.25), 1e-6);
  EXPECT_NEAR(n[1], 1.0 / std::sqrt(1.25), 1e-6);
  EXPECT_NEAR(std::sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]), 1.0, 1e-6);
}

TEST_F(GltfLoader, NegativeDeterminantReversesWindingAndFlipsTangentSign) {
  GltfBuilder b;
  std::map<std::string, int> attrs{{"POSITION", b.addFloats(kQuadP, "VEC3")}, {"NORMAL", b.addFloats(kQuadN, "VEC3")},
                                   {"TANGENT", b.addFloats({1, 0, 0, 1, 1, 0, 0, 1, 1, 0, 0, 1, 1, 0, 0, 1}, "VEC4")}};
  const int mesh = b.addMesh({GltfBuilder::primitive(attrs, b.addIndices(kQuadI))});
  b.addScene({b.addMeshNode(mesh, {{"scale", {-1, 1, 1}}})});
  const gltf::Asset a = load(b);
  const auto& p = a.primitives[0];
  EXPECT_EQ(p.indices, (std::vector<std::uint32_t>{0, 2, 1, 0, 3, 2}));
  // Counter-clockwise seen from the normal's side: the geometric normal agrees with the shading normal.
  const auto p0 = vertex(p.positions, p.indices[0]), p1 = vertex(p.positions, p.indices[1]), p2 = vertex(p.positions, p.indices[2]);
  const auto g = crossD({p1[0] - p0[0], p1[1] - p0[1], p1[2] - p0[2]}, {p2[0] - p0[0], p2[1] - p0[1], p2[2] - p0[2]});
  EXPECT_GT(g[2] * p.normals[2], 0.0);
  EXPECT_FLOAT_EQ(p.tangents[0], -1.0f);
  EXPECT_FLOAT_EQ(p.tangents[3], -1.0f);
}

TEST_F(GltfLoader, ZeroScaleNodeHidesItsMeshes) {
  const gltf::Asset a = load(quad({{"scale", {0, 0, 0}}}));
  EXPECT_TRUE(a.primitives.empty());
}

TEST_F(GltfLoader, StripsAndFansExpandPerTheSpec) {
  GltfBuilder b;
  std::vector<float> pos;
  for (int i = 0; i < 5; ++i) pos.insert(pos.end(), {float(i), float(i % 2), 0});
  const int strip = b.addMesh({GltfBuilder::primitive({{"POSITION", b.addFloats(pos, "VEC3")}}, -1, -1, 5)});
  const int fan = b.addMesh({GltfBuilder::primitive({{"POSITION", b.addFloats(pos, "VEC3")}}, b.addIndices({4, 3, 2, 1, 0}), -1, 6)});
  b.addScene({b.addMeshNode(strip), b.addMeshNode(fan)});
  const gltf::Asset a = load(b);
  ASSERT_EQ(a.primitives.size(), 2u);
  EXPECT_EQ(a.primitives[0].indices, (std::vector<std::uint32_t>{0, 1, 2, 1, 3, 2, 2, 3, 4}));
  EXPECT_EQ(a.primitives[1].indices, (std::vector<std::uint32_t>{3, 2, 4, 2, 1, 4, 1, 0, 4}));
}

TEST_F(GltfLoader, PointsAndLinesAreSkippedWithOneWarning) {
  GltfBuilder b;
  const int pos = b.addFloats(kQuadP, "VEC3");
  const int mesh = b.addMesh({GltfBuilder::primitive({{"POSITION", pos}}, -1, -1, 0), GltfBuilder::primitive({{"POSITION", pos}}, -1, -1, 1),
                              GltfBuilder::primitive({{"POSITION", pos}}, -1, -1, 3), GltfBuilder::primitive({{"POSITION", pos}}, b.addIndices(kQuadI))});
  b.addScene({b.addMeshNode(mesh)});
  const gltf::Asset a = load(b);
  EXPECT_EQ(a.primitives.size(), 1u);
  ASSERT_EQ(a.warnings.size(), 1u);
  EXPECT_CONTAINS(a.warnings[0], "3 point or line primitive(s) skipped");
}

TEST_F(GltfLoader, SkinsAndMorphTargetsWarnOnceEachAndRenderTheRestPose) {
  GltfBuilder b;
  const int pos = b.addFloats(kQuadP, "VEC3");
  json prim = GltfBuilder::primitive({{"POSITION", pos}}, b.addIndices(kQuadI));
  prim["targets"] = json::array({{{"POSITION", b.addFloats(std::vector<float>(12, 5.0f), "VEC3")}}});
  const int mesh = b.addMesh({prim});
  const int joint = b.addNode();
  b.doc["skins"] = json::array({{{"joints", {joint}}}});
  b.addScene({b.addMeshNode(mesh, {{"skin", 0}}), b.addMeshNode(mesh, {{"skin", 0}}), joint});
  const gltf::Asset a = load(b);
  ASSERT_EQ(a.primitives.size(), 2u);
  EXPECT_EQ(a.primitives[0].positions, kQuadP);
  ASSERT_EQ(a.warnings.size(), 2u);
  EXPECT_CONTAINS(a.warnings[0], "skins are ignored");
  EXPECT_CONTAINS(a.warnings[1], "morph targets are ignored");
}

// ---------------------------------------------------------------------------------------------
// Accessors

TEST_F(GltfLoader, EveryComponentTypeAndTheNormalizationFormulas) {
  GltfBuilder b;
  b.useExtension("KHR_mesh_quantization", true);
  // Three vertices per accessor; each POSITION type decoded generically.
  const std::vector<std::int8_t> i8 = {-128, 127, 64, 0, 0, 0, -127, 1, 2};
  const std::vector<std::uint8_t> u8 = {255, 0, 51, 0, 0, 0, 1, 2, 3};
  const std::vector<std::int16_t> i16 = {-32768, 32767, 16384, 0, 0, 0, 1, 1, 1};
  const std::vector<std::uint16_t> u16 = {65535, 0, 13107, 0, 0, 0, 1, 1, 1};
  const std::vector<std::uint32_t> idx = {0, 1, 2};
  struct Case {
    int accessor;
    std::vector<float> want;  // first vertex
  };
  std::vector<Case> cases = {
      {b.addAccessor(i8, 5120, "VEC3", true), {-1.0f, 1.0f, float(64 / 127.0)}},
      {b.addAccessor(u8, 5121, "VEC3", true), {1.0f, 0.0f, 0.2f}},
      {b.addAccessor(i16, 5122, "VEC3", true), {-1.0f, 1.0f, float(16384 / 32767.0)}},
      {b.addAccessor(u16, 5123, "VEC3", true), {1.0f, 0.0f, 0.2f}},
      {b.addAccessor(i8, 5120, "VEC3"), {-128, 127, 64}},
      {b.addAccessor(u16, 5123, "VEC3"), {65535, 0, 13107}},
      {b.addAccessor(std::vector<std::uint32_t>{7, 8, 9, 0, 0, 0, 1, 1, 1}, 5125, "VEC3"), {7, 8, 9}},
  };
  std::vector<json> prims;
  for (const Case& c : cases) prims.push_back(GltfBuilder::primitive({{"POSITION", c.accessor}}, b.addIndices(idx)));
  b.addScene({b.addMeshNode(b.addMesh(prims))});
  const gltf::Asset a = load(b);
  ASSERT_EQ(a.primitives.size(), cases.size());
  for (std::size_t k = 0; k < cases.size(); ++k)
    for (int c = 0; c < 3; ++c) EXPECT_NEAR(a.primitives[k].positions[std::size_t(c)], cases[k].want[std::size_t(c)], 1e-6) << "case " << k;
  EXPECT_TRUE(a.warnings.empty()) << a.warnings[0];  // KHR_mesh_quantization is supported
}

TEST_F(GltfLoader, QuantizedUvsAndColorsWithAlphaOne) {
  GltfBuilder b;
  std::map<std::string, int> attrs{
      {"POSITION", b.addFloats(kQuadP, "VEC3")},
      {"TEXCOORD_0", b.addAccessor(std::vector<std::uint8_t>{0, 255, 255, 255, 255, 0, 0, 0}, 5121, "VEC2", true)},
      {"TEXCOORD_1", b.addAccessor(std::vector<std::uint16_t>{0, 65535, 65535, 65535, 65535, 0, 0, 0}, 5123, "VEC2", true)},
      {"COLOR_0", b.addAccessor(std::vector<std::uint8_t>{255, 0, 51, 0, 255, 0, 0, 0, 255, 255, 255, 255}, 5121, "VEC3", true)}};
  std::map<std::string, int> attrs2{{"POSITION", attrs["POSITION"]},
                                    {"COLOR_0", b.addAccessor(std::vector<std::uint16_t>(16, 32768), 5123, "VEC4", true)}};
  b.addScene({b.addMeshNode(b.addMesh({GltfBuilder::primitive(attrs, b.addIndices(kQuadI)), GltfBuilder::primitive(attrs2, b.addIndices(kQuadI))}))});
  const gltf::Asset a = load(b);
  ASSERT_EQ(a.primitives.size(), 2u);
  EXPECT_EQ(a.primitives[0].uv0, kQuadUv);
  EXPECT_EQ(a.primitives[0].uv1, kQuadUv);
  const auto& c = a.primitives[0].color0;
  ASSERT_EQ(c.size(), 16u);
  EXPECT_FLOAT_EQ(c[0], 1.0f);
  EXPECT_FLOAT_EQ(c[2], 0.2f);
  EXPECT_FLOAT_EQ(c[3], 1.0f);
  EXPECT_FLOAT_EQ(c[15], 1.0f);
  EXPECT_NEAR(a.primitives[1].color0[3], 32768 / 65535.0, 1e-7);
}

TEST_F(GltfLoader, InterleavedAttributesWithByteStride) {
  GltfBuilder b;
  std::vector<float> inter;
  for (int v = 0; v < 4; ++v) {
    inter.insert(inter.end(), kQuadP.begin() + 3 * v, kQuadP.begin() + 3 * v + 3);
    inter.insert(inter.end(), kQuadN.begin() + 3 * v, kQuadN.begin() + 3 * v + 3);
  }
  const int view = b.addBufferView(inter.data(), inter.size() * 4, 24);
  b.doc["accessors"].push_back({{"bufferView", view}, {"componentType", 5126}, {"count", 4}, {"type", "VEC3"}});
  b.doc["accessors"].push_back({{"bufferView", view}, {"byteOffset", 12}, {"componentType", 5126}, {"count", 4}, {"type", "VEC3"}});
  b.addScene({b.addMeshNode(b.addMesh({GltfBuilder::primitive({{"POSITION", 0}, {"NORMAL", 1}}, b.addIndices(kQuadI))}))});
  const gltf::Asset a = load(b);
  EXPECT_EQ(a.primitives[0].positions, kQuadP);
  EXPECT_EQ(a.primitives[0].normals, kQuadN);
}

TEST_F(GltfLoader, SparseAccessorsWithAndWithoutBufferView) {
  GltfBuilder b;
  const int base = b.addFloats(kQuadP, "VEC3");
  const std::vector<std::uint16_t> which = {2};
  const std::vector<float> values = {5, 6, 7};
  const int iv = b.addBufferView(which.data(), 2), vv = b.addBufferView(values.data(), 12);
  json sparse = {{"count", 1}, {"indices", {{"bufferView", iv}, {"componentType", 5123}}}, {"values", {{"bufferView", vv}}}};
  b.doc["accessors"][std::size_t(base)]["sparse"] = sparse;
  // Without a bufferView: zeros, then the sparse values.
  b.doc["accessors"].push_back({{"componentType", 5126}, {"count", 4}, {"type", "VEC3"}, {"sparse", sparse}});
  const int zeros = int(b.doc["accessors"].size()) - 1;
  b.addScene({b.addMeshNode(b.addMesh({GltfBuilder::primitive({{"POSITION", base}}, b.addIndices(kQuadI)),
                                       GltfBuilder::primitive({{"POSITION", zeros}}, b.addIndices(kQuadI))}))});
  const gltf::Asset a = load(b);
  std::vector<float> want = kQuadP;
  want[6] = 5, want[7] = 6, want[8] = 7;
  EXPECT_EQ(a.primitives[0].positions, want);
  EXPECT_EQ(a.primitives[1].positions, (std::vector<float>{0, 0, 0, 0, 0, 0, 5, 6, 7, 0, 0, 0}));
}

// ---------------------------------------------------------------------------------------------
// Materials, textures, images

TEST_F(GltfLoader, MaterialsSamplersAndTexturesAreFilledCompletely) {
  GltfBuilder b;
  const int img = b.addImage(brdfcl::test::encodePng8(2, 2, 4, std::vector<std::uint8_t>(16, 200)));
  const int smp = b.addSampler({{"magFilter", 9728}, {"minFilter", 9985}, {"wrapS", 33071}, {"wrapT", 33648}});
  b.addSampler({{"minFilter", 9729}});
  b.addSampler({{"minFilter", 9986}});
  const int tex = b.addTexture(img, smp);
  b.useExtension("KHR_texture_transform");
  b.useExtension("KHR_materials_sheen");
  b.useExtension("KHR_materials_clearcoat");
  b.useExtension("KHR_materials_anisotropy");
  b.useExtension("KHR_materials_emissive_strength");
  json ti = {{"index", tex}, {"texCoord", 1}};
  json tt = {{"index", tex}, {"extensions", {{"KHR_texture_transform", {{"offset", {0.5, 0.25}}, {"rotation", 0.3}, {"scale", {2, 3}}, {"texCoord", 1}}}}}};
  b.addMaterial({{"name", "full"},
                 {"pbrMetallicRoughness", {{"baseColorFactor", {0.1, 0.2, 0.3, 0.4}}, {"baseColorTexture", tt}, {"metallicFactor", 0.25},
                                           {"roughnessFactor", 0.75}, {"metallicRoughnessTexture", ti}}},
                 {"normalTexture", {{"index", tex}, {"scale", 0.5}}},
                 {"occlusionTexture", {{"index", tex}, {"strength", 0.6}}},
                 {"emissiveTexture", ti},
                 {"emissiveFactor", {1, 0.5, 0}},
                 {"alphaMode", "MASK"},
                 {"alphaCutoff", 0.3},
                 {"doubleSided", true},
                 {"extensions",
                  {{"KHR_materials_sheen", {{"sheenColorFactor", {1, 0.329, 0.1}}, {"sheenColorTexture", ti}, {"sheenRoughnessFactor", 0.8}, {"sheenRoughnessTexture", ti}}},
                   {"KHR_materials_clearcoat", {{"clearcoatFactor", 0.9}, {"clearcoatTexture", ti}, {"clearcoatRoughnessFactor", 0.1}, {"clearcoatRoughnessTexture", ti},
                                                {"clearcoatNormalTexture", {{"index", tex}, {"scale", 0.7}}}}},
                   {"KHR_materials_anisotropy", {{"anisotropyStrength", 0.6}, {"anisotropyRotation", 1.5}, {"anisotropyTexture", ti}}},
                   {"KHR_materials_emissive_strength", {{"emissiveStrength", 5}}}}}});
  b.addMaterial({{"name", "defaults"}});
  b.addScene({b.addMeshNode(b.addTriangles(kQuadP, kQuadI, 0, kQuadN, kQuadUv))});
  const gltf::Asset a = load(b);
  ASSERT_EQ(a.materials.size(), 2u);
  const gltf::Material& m = a.materials[0];
  EXPECT_EQ(m.name, "full");
  EXPECT_EQ(m.baseColorFactor, (std::array<float, 4>{0.1f, 0.2f, 0.3f, 0.4f}));
  EXPECT_EQ(m.baseColorTexture.texture, tex);
  EXPECT_EQ(m.baseColorTexture.texCoord, 1);  // the transform's override
  EXPECT_EQ(m.baseColorTexture.transform.offset, (std::array<float, 2>{0.5f, 0.25f}));
  EXPECT_FLOAT_EQ(m.baseColorTexture.transform.rotation, 0.3f);
  EXPECT_EQ(m.baseColorTexture.transform.scale, (std::array<float, 2>{2.0f, 3.0f}));
  EXPECT_FLOAT_EQ(m.metallicFactor, 0.25f);
  EXPECT_FLOAT_EQ(m.roughnessFactor, 0.75f);
  EXPECT_EQ(m.metallicRoughnessTexture.texCoord, 1);
  EXPECT_FLOAT_EQ(m.normalTexture.value, 0.5f);
  EXPECT_EQ(m.normalTexture.texCoord, 0);
  EXPECT_FLOAT_EQ(m.occlusionTexture.value, 0.6f);
  EXPECT_TRUE(m.emissiveTexture.present());
  EXPECT_EQ(m.emissiveFactor, (std::array<float, 3>{1.0f, 0.5f, 0.0f}));
  EXPECT_FLOAT_EQ(m.emissiveStrength, 5.0f);
  EXPECT_EQ(m.alphaMode, gltf::AlphaMode::Mask);
  EXPECT_FLOAT_EQ(m.alphaCutoff, 0.3f);
  EXPECT_TRUE(m.doubleSided);
  EXPECT_EQ(m.sheenColorFactor, (std::array<float, 3>{1.0f, 0.329f, 0.1f}));
  EXPECT_FLOAT_EQ(m.sheenRoughnessFactor, 0.8f);
  EXPECT_TRUE(m.sheenColorTexture.present() && m.sheenRoughnessTexture.present());
  EXPECT_FLOAT_EQ(m.clearcoatFactor, 0.9f);
  EXPECT_FLOAT_EQ(m.clearcoatRoughnessFactor, 0.1f);
  EXPECT_TRUE(m.clearcoatTexture.present() && m.clearcoatRoughnessTexture.present());
  EXPECT_FLOAT_EQ(m.clearcoatNormalTexture.value, 0.7f);
  EXPECT_FLOAT_EQ(m.anisotropyStrength, 0.6f);
  EXPECT_FLOAT_EQ(m.anisotropyRotation, 1.5f);
  EXPECT_EQ(m.anisotropyTexture.texCoord, 1);
  const gltf::Material& d = a.materials[1];
  EXPECT_EQ(d.baseColorFactor, (std::array<float, 4>{1, 1, 1, 1}));
  EXPECT_FLOAT_EQ(d.metallicFactor, 1.0f);
  EXPECT_EQ(d.alphaMode, gltf::AlphaMode::Opaque);
  EXPECT_FALSE(d.needsTangents());
  ASSERT_EQ(a.samplers.size(), 3u);
  EXPECT_EQ(a.samplers[0].wrapS, gltf::Wrap::ClampToEdge);
  EXPECT_EQ(a.samplers[0].wrapT, gltf::Wrap::MirroredRepeat);
  EXPECT_TRUE(a.samplers[0].magNearest);
  EXPECT_FALSE(a.samplers[0].minNearest);
  EXPECT_TRUE(a.samplers[0].mipmaps && a.samplers[0].mipNearest);
  EXPECT_FALSE(a.samplers[1].mipmaps);
  EXPECT_EQ(a.samplers[1].wrapS, gltf::Wrap::Repeat);
  EXPECT_TRUE(a.samplers[2].minNearest && a.samplers[2].mipmaps && !a.samplers[2].mipNearest);
  ASSERT_EQ(a.textures.size(), 1u);
  EXPECT_EQ(a.textures[0].image, img);
  EXPECT_EQ(a.textures[0].sampler, smp);
  ASSERT_EQ(a.images.size(), 1u);
  EXPECT_EQ(a.images[0].rgba[0], 200 * 257);
  EXPECT_EQ(a.primitives[0].material, 0);
  EXPECT_TRUE(a.warnings.empty());
}

TEST_F(GltfLoader, ImagesDecode8And16BitPngAndJpegToRgba16) {
  GltfBuilder b;
  const int grey8 = b.addImage(brdfcl::test::encodePng8(2, 1, 1, {10, 250}), "image/png", "grey.png");
  const int rgba16 = b.addImage(brdfcl::test::encodePng16(1, 2, 4, {1, 2, 3, 4, 65535, 40000, 0, 7}), "image/png", "deep.png");
  const int jpeg = b.addImage(brdfcl::test::encodeJpeg(8, 8, 3, std::vector<std::uint8_t>(192, 128)), "image/jpeg", "flat.jpg");
  for (int i : {grey8, rgba16, jpeg}) b.addTexture(i);
  b.addScene({b.addMeshNode(b.addTriangles(kQuadP, kQuadI))});
  for (Storage s : {Storage::ExternalFiles, Storage::DataUris, Storage::Glb}) {
    const gltf::Asset a = load(b, s);
    ASSERT_EQ(a.images.size(), 3u);
    const gltf::Image& g = a.images[0];
    EXPECT_EQ(g.width, 2);
    EXPECT_EQ(g.height, 1);
    EXPECT_EQ(g.bits, 8);
    EXPECT_EQ(g.rgba, (std::vector<std::uint16_t>{2570, 2570, 2570, 65535, 64250, 64250, 64250, 65535}));
    const gltf::Image& d = a.images[1];
    EXPECT_EQ(d.bits, 16);
    EXPECT_EQ(d.height, 2);
    EXPECT_EQ(d.rgba, (std::vector<std::uint16_t>{1, 2, 3, 4, 65535, 40000, 0, 7}));
    const gltf::Image& j = a.images[2];
    EXPECT_EQ(j.width, 8);
    EXPECT_NEAR(j.rgba[0], 128 * 257, 2 * 257);
    EXPECT_EQ(j.rgba[3], 65535);
    if (s == Storage::ExternalFiles) EXPECT_EQ(g.name, "grey.png");
  }
}

// ---------------------------------------------------------------------------------------------
// Scenes, cameras, lights, variants, extensions

TEST_F(GltfLoader, SceneChoiceDefaultsToTheFilesSceneElseZero) {
  GltfBuilder b;
  const int mesh = b.addTriangles(kQuadP, kQuadI);
  const int n0 = b.addMeshNode(mesh), n1 = b.addMeshNode(mesh, {{"translation", {0, 0, 3}}});
  b.addScene({n0});
  b.addScene({n0, n1});
  b.doc["scene"] = 1;
  EXPECT_EQ(load(b).primitives.size(), 2u);
  gltf::LoadOptions o;
  o.scene = 0;
  EXPECT_EQ(load(b, Storage::DataUris, o).primitives.size(), 1u);
  b.doc.erase("scene");
  EXPECT_EQ(load(b).primitives.size(), 1u);
}

TEST_F(GltfLoader, CamerasInDepthFirstOrderWithWorldMatrices) {
  GltfBuilder b;
  const int persp = b.addCamera({{"type", "perspective"}, {"name", "p"}, {"perspective", {{"yfov", 0.5}, {"znear", 0.1}, {"zfar", 100}, {"aspectRatio", 1.5}}}});
  const int ortho = b.addCamera({{"type", "orthographic"}, {"orthographic", {{"xmag", 2}, {"ymag", 3}, {"znear", 0}, {"zfar", 10}}}});
  const int child = b.addNode({{"camera", ortho}, {"translation", {0, 1, 0}}});
  const int parent = b.addNode({{"camera", persp}, {"translation", {0, 0, 5}}, {"children", {child}}});
  const int other = b.addNode({{"camera", persp}});
  b.addScene({parent, other});
  const gltf::Asset a = load(b);
  ASSERT_EQ(a.cameras.size(), 3u);
  EXPECT_EQ(a.cameras[0].node, parent);
  EXPECT_EQ(a.cameras[1].node, child);
  EXPECT_EQ(a.cameras[2].node, other);
  EXPECT_EQ(a.cameras[0].name, "p");
  EXPECT_FALSE(a.cameras[0].orthographic);
  EXPECT_DOUBLE_EQ(a.cameras[0].yfov, 0.5);
  EXPECT_DOUBLE_EQ(a.cameras[0].aspectRatio, 1.5);
  EXPECT_DOUBLE_EQ(a.cameras[0].znear, 0.1);
  EXPECT_DOUBLE_EQ(a.cameras[0].zfar, 100);
  EXPECT_TRUE(a.cameras[1].orthographic);
  EXPECT_DOUBLE_EQ(a.cameras[1].xmag, 2);
  EXPECT_DOUBLE_EQ(a.cameras[1].ymag, 3);
  EXPECT_DOUBLE_EQ(a.cameras[1].world[13], 1);  // translation column
  EXPECT_DOUBLE_EQ(a.cameras[1].world[14], 5);
}

TEST_F(GltfLoader, PunctualLightsArePlacedInWorldSpace) {
  GltfBuilder b;
  const int spot = b.addLight({{"type", "spot"}, {"color", {1, 0.5, 0.25}}, {"intensity", 20}, {"range", 7},
                               {"spot", {{"innerConeAngle", 0.1}, {"outerConeAngle", 0.5}}}});
  const int sun = b.addLight({{"type", "directional"}});
  // Rotated 90 degrees about +X: local -Z becomes world +Y... no: -Z rotated by +90 about X is (0, 1, 0).
  const double s = std::sqrt(0.5);
  const int n0 = b.addNode({{"translation", {1, 2, 3}}, {"extensions", {{"KHR_lights_punctual", {{"light", spot}}}}}});
  const int n1 = b.addNode({{"rotation", {s, 0, 0, s}}, {"extensions", {{"KHR_lights_punctual", {{"light", sun}}}}}});
  b.addScene({n0, n1});
  const gltf::Asset a = load(b);
  ASSERT_EQ(a.lights.size(), 2u);
  const brdfcl::Light& l = a.lights[0];
  EXPECT_EQ(l.type, brdfcl::Light::Type::Spot);
  EXPECT_EQ(l.position, (std::array<float, 3>{1, 2, 3}));
  EXPECT_EQ(l.direction, (std::array<float, 3>{0, 0, -1}));
  EXPECT_EQ(l.color, (std::array<float, 3>{1, 0.5f, 0.25f}));
  EXPECT_FLOAT_EQ(l.intensity, 20);
  EXPECT_FLOAT_EQ(l.range, 7);
  EXPECT_FLOAT_EQ(l.innerCone, 0.1f);
  EXPECT_FLOAT_EQ(l.outerCone, 0.5f);
  EXPECT_EQ(a.lights[1].type, brdfcl::Light::Type::Directional);
  EXPECT_NEAR(a.lights[1].direction[1], 1.0, 1e-6);
  EXPECT_NEAR(a.lights[1].direction[2], 0.0, 1e-6);
}

GltfBuilder withVariants() {
  GltfBuilder b;
  b.useExtension("KHR_materials_variants");
  b.doc["extensions"]["KHR_materials_variants"]["variants"] = json::array({{{"name", "red"}}, {{"name", "blue"}}});
  b.addMaterial({{"name", "default"}});
  b.addMaterial({{"name", "red"}});
  b.addMaterial({{"name", "blue"}});
  const int pos = b.addFloats(kQuadP, "VEC3");
  json prim = GltfBuilder::primitive({{"POSITION", pos}}, b.addIndices(kQuadI), 0);
  prim["extensions"]["KHR_materials_variants"]["mappings"] = json::array({{{"material", 1}, {"variants", {0}}}, {{"material", 2}, {"variants", {1}}}});
  b.addScene({b.addMeshNode(b.addMesh({prim}))});
  return b;
}

TEST_F(GltfLoader, VariantsSelectPerPrimitiveMaterials) {
  const GltfBuilder b = withVariants();
  gltf::LoadOptions o;
  EXPECT_EQ(load(b).primitives[0].material, 0);
  EXPECT_EQ(load(b).variants, (std::vector<std::string>{"red", "blue"}));
  o.variant = "red";
  EXPECT_EQ(load(b, Storage::DataUris, o).primitives[0].material, 1);
  o.variant = "blue";
  EXPECT_EQ(load(b, Storage::DataUris, o).primitives[0].material, 2);
}

TEST_F(GltfLoader, UnsupportedUsedExtensionsGiveOneWarning) {
  GltfBuilder b = quad();
  for (const char* e : {"KHR_materials_transmission", "KHR_materials_volume", "KHR_materials_sheen", "KHR_materials_ior"}) b.useExtension(e);
  const gltf::Asset a = load(b);
  ASSERT_EQ(a.warnings.size(), 1u);
  EXPECT_CONTAINS(a.warnings[0], "extensionsUsed: brdfcl ignores KHR_materials_transmission, KHR_materials_volume, KHR_materials_ior;");
}

TEST_F(GltfLoader, ADeepChainOfNodesLoadsWithoutRecursion) {
  GltfBuilder b;
  const int mesh = b.addTriangles(kQuadP, kQuadI);
  const int n = 20000;
  for (int i = 0; i < n; ++i) b.addNode(i + 1 < n ? json{{"children", {i + 1}}, {"translation", {0, 0, 0.001}}} : json{{"mesh", mesh}});
  b.addScene({0});
  const gltf::Asset a = load(b);
  ASSERT_EQ(a.primitives.size(), 1u);
  EXPECT_NEAR(a.primitives[0].positions[2], 0.001 * (n - 1), 1e-3);
}

// ---------------------------------------------------------------------------------------------
// Tangents

// A UV sphere: u = phi / 2pi around +Y, v = theta / pi from the top (glTF's v runs down the image).
struct Sphere {
  std::vector<float> p, n, uv;
  std::vector<std::uint32_t> idx;
};
Sphere uvSphere(int rings, int segments) {
  Sphere s;
  for (int r = 0; r <= rings; ++r)
    for (int k = 0; k <= segments; ++k) {
      const double th = kPi * r / rings, ph = 2 * kPi * k / segments;
      const double x = std::sin(th) * std::cos(ph), y = std::cos(th), z = -std::sin(th) * std::sin(ph);
      s.p.insert(s.p.end(), {float(x), float(y), float(z)});
      s.n.insert(s.n.end(), {float(x), float(y), float(z)});
      s.uv.insert(s.uv.end(), {float(double(k) / segments), float(double(r) / rings)});
    }
  const int w = segments + 1;
  for (int r = 0; r < rings; ++r)
    for (int k = 0; k < segments; ++k) {
      const std::uint32_t a = std::uint32_t(r * w + k), b = a + 1, c = a + std::uint32_t(w), d = c + 1;
      s.idx.insert(s.idx.end(), {a, c, b, b, c, d});  // counter-clockwise seen from outside
    }
  return s;
}

GltfBuilder sphereWithNormalMap(const Sphere& s, bool withNormals) {
  GltfBuilder b;
  const int tex = b.addTexture(b.addImage(brdfcl::test::encodePng8(1, 1, 3, {128, 128, 255})));
  const int mat = b.addMaterial({{"normalTexture", {{"index", tex}}}});
  b.addScene({b.addMeshNode(b.addTriangles(s.p, s.idx, mat, withNormals ? s.n : std::vector<float>{}, s.uv))});
  return b;
}

TEST_F(GltfTangents, UvSphereMatchesAnalyticTangents) {
  const Sphere s = uvSphere(32, 64);
  for (bool withNormals : {true, false}) {
    const gltf::Asset a = load(sphereWithNormalMap(s, withNormals));
    ASSERT_EQ(a.primitives.size(), 1u);
    const gltf::Primitive& p = a.primitives[0];
    EXPECT_TRUE(p.generatedTangents);
    ASSERT_EQ(p.tangents.size(), 4 * p.vertexCount());
    double worst = 0, sum = 0;
    int wrongSign = 0, checked = 0;
    for (std::size_t v = 0; v < p.vertexCount(); ++v) {
      const auto P = vertex(p.positions, v);
      const double rxz = std::hypot(P[0], P[2]);
      if (rxz < 0.2) continue;  // the poles have no dP/du
      // dP/du is along (-sin ph, 0, -cos ph) with x = r cos ph, z = -r sin ph; dP/dv points down (-Y side).
      const std::array<double, 3> T = {P[2] / rxz, 0.0, -P[0] / rxz};
      const auto got = vertex(p.tangents, v, 4);
      worst = std::max(worst, angleDeg(got, T));
      sum += angleDeg(got, T);
      // glTF: cross(N, T) * w is the bitangent, pointing where v decreases (up the image): +Y here.
      const auto N = withNormals ? vertex(p.normals, v) : P;
      const auto B = crossD(N, got);
      wrongSign += (B[1] * p.tangents[4 * v + 3] > 0) ? 0 : 1;
      ++checked;
    }
    EXPECT_GT(checked, 1000);
    std::printf("[tangents] UV sphere %s normals: mean %.3f deg, max %.3f deg over %d vertices\n", withNormals ? "with" : "without",
                sum / checked, worst, checked);
    EXPECT_LT(sum / checked, 0.5);
    EXPECT_LT(worst, 4.0);  // the rings next to the poles, where triangles are thin
    EXPECT_EQ(wrongSign, 0);
  }
}

TEST_F(GltfTangents, NotGeneratedWithoutANeedOrWithoutTheUvSet) {
  GltfBuilder b = quad({}, 0);
  b.addMaterial({{"name", "plain"}});
  EXPECT_TRUE(load(b).primitives[0].tangents.empty());
  GltfBuilder c;
  const int tex = c.addTexture(c.addImage(brdfcl::test::encodePng8(1, 1, 3, {128, 128, 255})));
  c.addMaterial({{"normalTexture", {{"index", tex}, {"texCoord", 1}}}});  // TEXCOORD_1 is absent
  c.addScene({c.addMeshNode(c.addTriangles(kQuadP, kQuadI, 0, kQuadN, kQuadUv))});
  EXPECT_TRUE(load(c).primitives[0].tangents.empty());
  GltfBuilder d;
  d.addMaterial({{"extensions", {{"KHR_materials_anisotropy", {{"anisotropyStrength", 0.5}}}}}});
  d.addScene({d.addMeshNode(d.addTriangles(kQuadP, kQuadI, 0, kQuadN, kQuadUv))});
  const gltf::Asset ad = load(d);
  const auto& p = ad.primitives[0];
  ASSERT_EQ(p.tangents.size(), 16u);
  EXPECT_TRUE(p.generatedTangents);
  EXPECT_EQ((std::vector<float>(p.tangents.begin(), p.tangents.begin() + 4)), (std::vector<float>{1, 0, 0, 1}));
}

TEST_F(GltfTangents, MirroredUvsSplitSharedVertices) {
  // Two quads sharing the middle edge; the right one has u mirrored (u decreasing with x).
  gltf::Primitive p;
  p.positions = {0, 0, 0, 1, 0, 0, 2, 0, 0, 0, 1, 0, 1, 1, 0, 2, 1, 0};
  p.normals = {0, 0, 1, 0, 0, 1, 0, 0, 1, 0, 0, 1, 0, 0, 1, 0, 0, 1};
  p.uv0 = {0, 1, 1, 1, 0, 1, 0, 0, 1, 0, 0, 0};
  p.indices = {0, 1, 4, 0, 4, 3, 1, 2, 5, 1, 5, 4};
  brdfcl::gltf::detail::generateTangents(p, 0);
  ASSERT_EQ(p.vertexCount(), 8u);  // vertices 1 and 4 were split
  ASSERT_EQ(p.tangents.size(), 32u);
  EXPECT_EQ(p.indices[6], 6u);
  EXPECT_EQ(p.indices[11], 7u);
  EXPECT_FLOAT_EQ(p.tangents[4 * 0], 1.0f);   // left: T = +X
  EXPECT_FLOAT_EQ(p.tangents[4 * 1], 1.0f);   // the shared vertex keeps the left side
  EXPECT_FLOAT_EQ(p.tangents[4 * 6], -1.0f);  // its copy: T = -X
  EXPECT_FLOAT_EQ(p.tangents[4 * 2], -1.0f);
  EXPECT_FLOAT_EQ(p.tangents[4 * 0 + 3], 1.0f);
  EXPECT_FLOAT_EQ(p.tangents[4 * 2 + 3], -1.0f);  // mirrored: the bitangent sign flips
  EXPECT_EQ(vertex(p.positions, 6), vertex(p.positions, 1));
}

TEST_F(GltfTangents, DegenerateUvsFallBackToAPerpendicular) {
  gltf::Primitive p;
  p.positions = kQuadP;
  p.normals = {0, 0.6f, 0.8f, 0, 0.6f, 0.8f, 0, 0.6f, 0.8f, 0, 0.6f, 0.8f};
  p.uv0 = std::vector<float>(8, 0.5f);
  p.indices = kQuadI;
  brdfcl::gltf::detail::generateTangents(p, 0);
  for (std::size_t v = 0; v < 4; ++v) {
    const auto t = vertex(p.tangents, v, 4), n = vertex(p.normals, v);
    EXPECT_NEAR(t[0] * n[0] + t[1] * n[1] + t[2] * n[2], 0.0, 1e-6);
    EXPECT_NEAR(std::sqrt(t[0] * t[0] + t[1] * t[1] + t[2] * t[2]), 1.0, 1e-6);
    EXPECT_TRUE(std::isfinite(p.tangents[4 * v + 3]));
  }
}

// Regenerates the tangents of the assets that ship TANGENTs and compares directions and signs.
TEST_F(GltfTangents, GeneratedTangentsAgreeWithTheAnisotropyAssets) {
  for (const char* rel : {"AnisotropyStrengthTest/glTF-Binary/AnisotropyStrengthTest.glb",
                          "AnisotropyRotationTest/glTF-Binary/AnisotropyRotationTest.glb"}) {
    const std::string path = brdfcl::test::assetPath(rel);
    if (path.empty()) GTEST_SKIP() << brdfcl::test::missingAsset(rel);
    const gltf::Asset a = gltf::load(path);
    double sum = 0, worst = 0;
    std::size_t n = 0, signs = 0;
    for (const gltf::Primitive& file : a.primitives) {
      if (file.tangents.empty() || file.uv0.empty() || file.normals.empty()) continue;
      gltf::Primitive mine = file;
      mine.tangents.clear();
      brdfcl::gltf::detail::generateTangents(mine, 0);
      for (std::size_t v = 0; v < file.vertexCount(); ++v) {
        const double d = angleDeg(vertex(file.tangents, v, 4), vertex(mine.tangents, v, 4));
        sum += d;
        worst = std::max(worst, d);
        signs += file.tangents[4 * v + 3] == mine.tangents[4 * v + 3] ? 1 : 0;
        ++n;
      }
    }
    ASSERT_GT(n, 0u) << rel;
    const double mean = sum / double(n);
    std::printf("[tangents] %s: %zu vertices, mean %.3f deg, max %.3f deg, w agrees %.2f%%\n", rel, n, mean, worst,
                100.0 * double(signs) / double(n));
    EXPECT_LT(mean, 5.0) << rel;
    EXPECT_GT(double(signs) / double(n), 0.99) << rel;
  }
}

// ---------------------------------------------------------------------------------------------
// Errors: one line, the file, the JSON path or object

TEST_F(GltfErrors, BadJsonAndNotGltf) {
  EXPECT_CONTAINS(bytesError("{\"asset\": ", "bad.gltf"), "bad.gltf: invalid JSON: ");
  EXPECT_CONTAINS(bytesError("[1, 2]", "arr.gltf"), "arr.gltf: expected a glTF JSON object at the top level, got an array");
  const std::string m = bytesError("{\"asset\": {}}", "nover.gltf");
  EXPECT_CONTAINS(m, "nover.gltf: ");
  EXPECT_CONTAINS(m, "re-export it");
  const std::string deep = "{\"asset\": {\"version\": \"2.0\"}, \"extras\": " + std::string(100000, '[') + std::string(100000, ']') + "}";
  EXPECT_CONTAINS(bytesError(deep, "deep.gltf"), "deep.gltf: the JSON nests deeper than 128 levels (in extras?); glTF needs far fewer: re-export the file");
  EXPECT_CONTAINS(errorOf([&] { gltf::load(scratch.path("absent.gltf")); }), "cannot read '");
  EXPECT_CONTAINS(errorOf([&] { gltf::load(scratch.path("absent.gltf")); }), "absent.gltf': No such file or directory");
}

// Each case edits a valid document and names the message it must give (after "<file>: ").
TEST_F(GltfErrors, EveryStructuralCheckNamesItsJsonPath) {
  struct Case {
    const char* want;
    std::function<void(json&)> edit;
  };
  const std::vector<Case> cases = {
      {"extensionsRequired: expected an array of extension names, got 3", [](json& d) { d["extensionsRequired"] = 3; }},
      {"extensionsUsed[0]: expected an extension name, got 3", [](json& d) { d["extensionsUsed"] = {3}; }},
      {"buffers[0]: missing \"byteLength\"; re-export the file", [](json& d) { d["buffers"][0].erase("byteLength"); }},
      {"buffers[0].byteLength: expected an integer >= 0, got -4", [](json& d) { d["buffers"][0]["byteLength"] = -4; }},
      {"buffers[1]: no \"uri\" (only the first buffer of a .glb may omit it); re-export the file", [](json& d) { d["buffers"].push_back({{"byteLength", 4}}); }},
      {"bufferViews[0].buffer: buffer 3 does not exist (the file has 1); re-export the file", [](json& d) { d["bufferViews"][0]["buffer"] = 3; }},
      {"bufferViews[0].byteLength: expected at least 1, got 0; re-export the file", [](json& d) { d["bufferViews"][0]["byteLength"] = 0; }},
      {"accessors[0]: bufferView 17 does not exist (the file has 5); re-export the file", [](json& d) { d["accessors"][0]["bufferView"] = 17; }},
      {"accessors[0]: bufferViews[0].byteStride 4 is smaller than one element (12 bytes); re-export the file", [](json& d) { d["bufferViews"][0]["byteStride"] = 4; }},
      {"accessors[0].componentType: unsupported component type 5124; expected 5120, 5121, 5122, 5123, 5125 or 5126", [](json& d) { d["accessors"][0]["componentType"] = 5124; }},
      {"accessors[0].type: the POSITION accessor must be VEC3; re-export the file", [](json& d) { d["accessors"][0]["type"] = "VEC2"; }},
      {"accessors[1]: NORMAL has 3 elements, POSITION has 4; re-export the file", [](json& d) { d["accessors"][1]["count"] = 3; }},
      {"accessors[0]: indices must be SCALAR of 5121, 5123 or 5125 (unsigned byte, short or int); re-export the file", [](json& d) { d["meshes"][0]["primitives"][0]["indices"] = 0; }},
      {"primitive indices accessor out of bounds; the file is not valid glTF 2.0: re-export it", [](json& d) { d["meshes"][0]["primitives"][0]["indices"] = 99; }},
      {"accessors[0].sparse.count: expected 1 to 4 (the accessor's count), got 5; re-export the file", [](json& d) { d["accessors"][0]["sparse"] = {{"count", 5}, {"indices", {{"bufferView", 4}, {"componentType", 5125}}}, {"values", {{"bufferView", 0}}}}; }},
      {"accessors[0].sparse.indices.componentType: expected 5121, 5123 or 5125, got 5126", [](json& d) { d["accessors"][0]["sparse"] = {{"count", 1}, {"indices", {{"bufferView", 4}, {"componentType", 5126}}}, {"values", {{"bufferView", 0}}}}; }},
      {"accessors[0].sparse.indices: index 7 is out of range (count 4); re-export the file", [](json& d) { d["accessors"][0]["sparse"] = {{"count", 1}, {"indices", {{"bufferView", 4}, {"byteOffset", 4}, {"componentType", 5125}}}, {"values", {{"bufferView", 0}}}}; }},
      {"accessors[0].sparse: negative byteOffset; re-export the file", [](json& d) { d["accessors"][0]["sparse"] = {{"count", 1}, {"indices", {{"bufferView", 4}, {"byteOffset", -4}, {"componentType", 5125}}}, {"values", {{"bufferView", 0}}}}; }},
      {"nodes[0].matrix: expected 16 numbers, got 2", [](json& d) { d["nodes"][0]["matrix"] = {1, 2}; }},
      {"nodes[0].translation: expected 3 numbers, got 1", [](json& d) { d["nodes"][0]["translation"] = {1}; }},
      {"meshes[0].primitives[0].extensions.KHR_materials_variants.mappings: expected an array of mappings, got 3", [](json& d) { d["meshes"][0]["primitives"][0]["extensions"]["KHR_materials_variants"]["mappings"] = 3; d["extensions"]["KHR_materials_variants"]["variants"] = {{{"name", "v"}}}; }},
      {"meshes[0].primitives[0].mode: unknown primitive mode 7; expected 0 to 6", [](json& d) { d["meshes"][0]["primitives"][0]["mode"] = 7; }},
      {"meshes[0].primitives[0].material: material 2 does not exist (the file has 0); re-export the file", [](json& d) { d["meshes"][0]["primitives"][0]["material"] = 2; }},
      {"nodes[0].mesh: mesh 5 does not exist (the file has 1); re-export the file", [](json& d) { d["nodes"][0]["mesh"] = 5; }},
      {"nodes[0].camera: camera 0 does not exist (the file has 0); re-export the file", [](json& d) { d["nodes"][0]["camera"] = 0; }},
      {"nodes[0].children: node 9 does not exist (the file has 1); re-export the file", [](json& d) { d["nodes"][0]["children"] = {9}; }},
      {"nodes[0].rotation: the quaternion has zero or non-finite length; use a unit quaternion", [](json& d) { d["nodes"][0]["rotation"] = {0, 0, 0, 0}; }},
      {"nodes[1]: the world transform overflows; fix the node's transform", [](json& d) { d["nodes"][0]["scale"] = {1e308, 1, 1}; d["nodes"][0]["children"] = {1}; d["nodes"].push_back({{"scale", {1e308, 1, 1}}}); }},
      {"scenes[0].nodes: node 4 does not exist (the file has 1)", [](json& d) { d["scenes"][0]["nodes"] = {4}; }},
      {"scenes[0].nodes: nodes[0] is listed twice; re-export the file", [](json& d) { d["scenes"][0]["nodes"] = {0, 0}; }},
      {"scene: scene 2 does not exist (the file has 1); re-export the file", [](json& d) { d["scene"] = 2; }},
      {"samplers[0].magFilter: expected 9728 or 9729, got 9984", [](json& d) { d["samplers"] = {{{"magFilter", 9984}}}; }},
      {"samplers[0].wrapS: expected 33071, 33648 or 10497, got 1", [](json& d) { d["samplers"] = {{{"wrapS", 1}}}; }},
      {"textures[0].source: image 3 does not exist (the file has 0); re-export the file", [](json& d) { d["textures"] = {{{"source", 3}}}; }},
      {"materials[0].normalTexture: missing \"index\" (the texture); re-export the file", [](json& d) { d["materials"] = {{{"normalTexture", json::object()}}}; }},
      {"materials[0].emissiveTexture.index: texture 0 does not exist (the file has 0); re-export the file", [](json& d) { d["materials"] = {{{"emissiveTexture", {{"index", 0}}}}}; }},
      {"materials[0].normalTexture.texCoord: expected 0 or 1 (brdfcl reads TEXCOORD_0 and TEXCOORD_1), got 2", [](json& d) { d["textures"] = {json::object()}; d["materials"] = {{{"normalTexture", {{"index", 0}, {"texCoord", 2}}}}}; }},
      {"materials[0].occlusionTexture.strength: expected a number in [0, 1], got 2", [](json& d) { d["textures"] = {json::object()}; d["materials"] = {{{"occlusionTexture", {{"index", 0}, {"strength", 2}}}}}; }},
      {"materials[0].alphaMode: expected \"OPAQUE\", \"MASK\" or \"BLEND\", got string \"CLEAR\"", [](json& d) { d["materials"] = {{{"alphaMode", "CLEAR"}}}; }},
      {"materials[0].doubleSided: expected true or false, got 1", [](json& d) { d["materials"] = {{{"doubleSided", 1}}}; }},
      {"materials[0].extensions.KHR_materials_sheen: expected an object, got an array of 0 elements", [](json& d) { d["materials"] = {{{"extensions", {{"KHR_materials_sheen", json::array()}}}}}; }},
      {"materials[0].extensions.KHR_materials_anisotropy.anisotropyStrength: expected a number in [0, 1], got -1", [](json& d) { d["materials"] = {{{"extensions", {{"KHR_materials_anisotropy", {{"anisotropyStrength", -1}}}}}}}; }},
      {"Invalid camera type: \"fisheye\". Must be \"perspective\" or \"orthographic\"; the file is not valid glTF 2.0: re-export it", [](json& d) { d["cameras"] = {{{"type", "fisheye"}}}; d["nodes"][0]["camera"] = 0; }},
      {"'yfov' property is missing in OrthographicCamera; the file is not valid glTF 2.0: re-export it", [](json& d) { d["cameras"] = {{{"type", "perspective"}, {"perspective", {{"znear", 1}}}}}; d["nodes"][0]["camera"] = 0; }},
      {"nodes[0].extensions.KHR_lights_punctual.light: light 0 does not exist (the file has 0); re-export the file", [](json& d) { d["nodes"][0]["extensions"]["KHR_lights_punctual"]["light"] = 0; }},
      {"extensions.KHR_lights_punctual.lights[0].type: expected \"directional\", \"point\" or \"spot\", got string \"area\"", [](json& d) { d["extensions"]["KHR_lights_punctual"]["lights"] = {{{"type", "area"}}}; d["nodes"][0]["extensions"]["KHR_lights_punctual"]["light"] = 0; }},
      {"extensions.KHR_lights_punctual.lights[0].spot.innerConeAngle: expected a number below outerConeAngle (0.5), got 0.6", [](json& d) { d["extensions"]["KHR_lights_punctual"]["lights"] = {{{"type", "spot"}, {"spot", {{"innerConeAngle", 0.6}, {"outerConeAngle", 0.5}}}}}; d["nodes"][0]["extensions"]["KHR_lights_punctual"]["light"] = 0; }},
      {"extensions.KHR_materials_variants.variants[0].name: expected the variant's name as a string", [](json& d) { d["extensions"]["KHR_materials_variants"]["variants"] = {json::object()}; }},
  };
  for (const Case& c : cases) {
    GltfBuilder b = quad();
    b.addBufferView("\0\0\0\0\7\0\0\0", 8);  // bufferViews[4]: sparse indices 0 and 7
    std::string bin;
    json d = b.finished(Storage::DataUris, "", &bin);
    c.edit(d);
    const std::string p = scratch.path("e.gltf");
    GltfBuilder::writeFile(p, d.dump());
    gltf::LoadOptions o;
    if (std::string(c.want).find("mappings") != std::string::npos) o.variant = "v";  // mappings are read for a variant only
    EXPECT_EQ(errorOf([&] { gltf::load(p, o); }), p + ": " + c.want);
  }
}

TEST_F(GltfErrors, GlbHeaderAndChunks) {
  GltfBuilder b = quad();
  std::string bin;
  const std::string text = b.finished(Storage::Glb, "", &bin).dump();
  const std::string good = GltfBuilder::glb(text, bin);
  EXPECT_NO_THROW(gltf::loadFromMemory(good, "ok.glb", scratch.dir()));
  std::string magic = good;
  magic[0] = 'x';
  EXPECT_EQ(bytesError(magic, "m.glb"), scratch.path("m.glb") + ": not a GLB file (no glTF magic number); a .glb must start with 'glTF'");
  std::string version = good;
  version[4] = 1;
  EXPECT_CONTAINS(bytesError(version, "v.glb"), "v.glb: unsupported GLB version 1; brdfcl reads glTF 2.0 binaries (version 2)");
  EXPECT_CONTAINS(bytesError(good.substr(0, good.size() - 8), "t.glb"), "t.glb: truncated GLB file: the header says " + std::to_string(good.size()));
  EXPECT_CONTAINS(bytesError(good + "pad!", "long.glb"), "long.glb: the GLB header says");
  // A BIN chunk claiming more than the file holds, with a consistent total length.
  std::string chunk = good;
  const std::size_t jsonLen = std::uint8_t(good[12]) | std::uint8_t(good[13]) << 8 | std::uint8_t(good[14]) << 16;
  chunk[20 + jsonLen] = char(std::uint8_t(chunk[20 + jsonLen]) + 8);
  EXPECT_CONTAINS(bytesError(chunk, "c.glb"), "c.glb: truncated GLB chunk 1 (BIN): it claims");
  std::string json0 = good;
  json0[12] = char(0xFF), json0[13] = char(0xFF);
  EXPECT_CONTAINS(bytesError(json0, "j.glb"), "j.glb: truncated GLB chunk 0 (JSON)");
  EXPECT_CONTAINS(bytesError(good.substr(0, 10), "short.glb"), "short.glb: truncated GLB file (10 bytes");
  const std::string head16 = std::string("glTF", 4) + GltfBuilder::le32(2) + GltfBuilder::le32(16) + "abcd";
  EXPECT_CONTAINS(bytesError(head16, "h.glb"), "h.glb: truncated GLB file: no room for the JSON chunk; re-export the file");
  std::string notJson = good;
  notJson[16] = 'X';
  EXPECT_CONTAINS(bytesError(notJson, "nj.glb"), "nj.glb: GLB chunk 0 is not JSON; re-export the file");
  auto withTail = [&](const std::string& tail) {  // the JSON chunk, then `tail` as the rest of the file
    std::string g = good.substr(0, 20 + jsonLen) + tail;
    g.replace(8, 4, GltfBuilder::le32(std::uint32_t(g.size())));
    return g;
  };
  EXPECT_CONTAINS(bytesError(withTail("abcd"), "cut.glb"), "cut.glb: truncated GLB chunk 1: its 8-byte header is cut off; re-export the file");
  EXPECT_CONTAINS(bytesError(withTail(GltfBuilder::le32(4) + "XYZ!abcd"), "nb.glb"), "nb.glb: GLB chunk 1 is not BIN; re-export the file");
  EXPECT_CONTAINS(bytesError(withTail(GltfBuilder::le32(3) + std::string("BIN\0", 4) + "abcd"), "odd.glb"),
                  "odd.glb: GLB chunk 1 (BIN) has 3 bytes, not a non-zero multiple of 4; re-export the file");
  EXPECT_CONTAINS(bytesError(withTail(GltfBuilder::le32(4) + std::string("BIN\0", 4) + "abcd"), "small.glb"),
                  "small.glb: buffers[0].byteLength: 152 is more than the 4 bytes of the GLB's BIN chunk; re-export the file");
}

TEST_F(GltfErrors, BufferViewAccessorAndIndexOutOfRange) {
  {
    GltfBuilder b = quad();
    b.doc["bufferViews"][0]["byteLength"] = 100000;
    EXPECT_CONTAINS(loadError(b), "m.gltf: bufferViews[0]: bytes 0 + 100000 lie outside buffers[0] of");
  }
  {
    GltfBuilder b = quad();
    b.doc["accessors"][0]["count"] = 1000000000;  // a small file claiming a 12 GB accessor
    EXPECT_CONTAINS(loadError(b), "m.gltf: accessors[0]: 1000000000 elements of 12 bytes (stride 12) from byteOffset 0 run past the end of bufferViews[0] (48 bytes); re-export the file");
  }
  {
    GltfBuilder b = quad();
    b.doc["accessors"][0].erase("bufferView");
    b.doc["accessors"][0]["count"] = 1ull << 40;  // nothing bounds it but brdfcl's limit
    EXPECT_CONTAINS(loadError(b), "m.gltf: accessors[0]: count 1099511627776 without a bufferView is more than brdfcl's limit");
  }
  {
    GltfBuilder b = quad();
    b.doc["meshes"][0]["primitives"][0]["attributes"]["POSITION"] = 42;
    EXPECT_CONTAINS(loadError(b), "m.gltf: meshes[0].primitives[0].attributes.POSITION: accessor 42 does not exist (the file has 4)");
  }
  {
    GltfBuilder b;
    b.addScene({b.addMeshNode(b.addTriangles(kQuadP, {0, 1, 9}))});
    EXPECT_EQ(loadError(b), scratch.path("m.gltf") + ": accessors[1]: index 9 at position 2 is out of range (the primitive has 4 vertices); re-export the file");
  }
  {
    GltfBuilder b = quad();
    b.doc["meshes"][0]["primitives"][0]["attributes"].erase("POSITION");
    EXPECT_CONTAINS(loadError(b), "m.gltf: meshes[0].primitives[0].attributes: no POSITION");
  }
}

TEST_F(GltfErrors, MissingOrUnreadableBufferAndImage) {
  GltfBuilder b = quad();
  b.addTexture(b.addImage(brdfcl::test::encodePng8(1, 1, 3, {1, 2, 3}), "image/png", "wood.png"));
  const std::string p = write(b, "ext.gltf", Storage::ExternalFiles);
  std::filesystem::remove(scratch.path("wood.png"));
  EXPECT_EQ(errorOf([&] { gltf::load(p); }), p + ": images[0] ('wood.png'): cannot read 'wood.png': No such file or directory");
  std::filesystem::remove(scratch.path("ext.bin"));
  EXPECT_EQ(errorOf([&] { gltf::load(p); }), p + ": buffers[0]: cannot read 'ext.bin': No such file or directory");
  std::filesystem::create_directory(scratch.path("ext.bin"));
  EXPECT_EQ(errorOf([&] { gltf::load(p); }),
            p + ": buffers[0].uri 'ext.bin' is not a regular file (a directory, FIFO or device); name a file");
  std::filesystem::remove(scratch.path("ext.bin"));
  GltfBuilder::writeFile(scratch.path("ext.bin"), "short");
  EXPECT_CONTAINS(errorOf([&] { gltf::load(p); }), ": buffers[0]: 'ext.bin' has 5 bytes, but byteLength says");
}

TEST_F(GltfErrors, UndecodableImage) {
  GltfBuilder b = quad();
  b.addImage(brdfcl::test::encodePng8(1, 1, 3, {1, 2, 3}));
  b.addImage(brdfcl::test::encodePng8(1, 1, 3, {1, 2, 3}));
  b.addTexture(b.addImage("\x89PNG\r\n\x1a\n garbage", "image/png", "wood.png"));
  b.addTexture(0);
  for (Storage s : {Storage::ExternalFiles, Storage::Glb}) {
    const std::string m = loadError(b, s);
    EXPECT_CONTAINS(m, s == Storage::Glb ? "m.glb: images[2]: cannot decode the image (" : "m.gltf: images[2] ('wood.png'): cannot decode the image (");
    EXPECT_CONTAINS(m, "); save it as PNG or JPEG");
  }
}

TEST_F(GltfErrors, NonFiniteDataAndFactors) {
  {
    GltfBuilder b;
    std::vector<float> p = kQuadP;
    p[4] = std::nanf("");
    b.addScene({b.addMeshNode(b.addTriangles(p, kQuadI))});
    EXPECT_CONTAINS(loadError(b), "m.gltf: accessors[0]: POSITION element 1 component 1 is nan; the data is corrupt: re-export the file");
  }
  {
    GltfBuilder b;
    std::vector<float> uv = kQuadUv;
    uv[0] = INFINITY;
    b.addScene({b.addMeshNode(b.addTriangles(kQuadP, kQuadI, -1, kQuadN, uv))});
    EXPECT_CONTAINS(loadError(b), "m.gltf: accessors[2]: TEXCOORD_0 element 0 component 0 is inf");
  }
  {
    GltfBuilder b = quad({}, 0);
    b.addMaterial({{"pbrMetallicRoughness", {{"roughnessFactor", 1e39}}}});
    EXPECT_CONTAINS(loadError(b), "m.gltf: materials[0].pbrMetallicRoughness.roughnessFactor: expected a number in [0, 1], got 1e+39");
  }
  {
    GltfBuilder b = quad({}, 0);
    b.addMaterial({{"emissiveFactor", {0, -2, 0}}});
    EXPECT_CONTAINS(loadError(b), "m.gltf: materials[0].emissiveFactor[1]: expected a number >= 0, got -2");
  }
}

TEST_F(GltfErrors, CamerasWithBadProjections) {
  auto withCamera = [&](json camera) {
    GltfBuilder b = quad();
    b.addCamera(camera);
    b.doc["nodes"][0]["camera"] = 0;
    return loadError(b);
  };
  EXPECT_CONTAINS(withCamera({{"type", "perspective"}, {"perspective", {{"yfov", 1}, {"znear", 0.1}, {"aspectRatio", 0}}}}),
                  "m.gltf: cameras[0].perspective.aspectRatio: expected a number > 0, got 0");
  EXPECT_CONTAINS(withCamera({{"type", "perspective"}, {"perspective", {{"yfov", 1}, {"znear", 1}, {"zfar", 0.5}}}}),
                  "m.gltf: cameras[0].perspective.zfar: expected a number > znear (1), got 0.5; fix the camera's clipping planes");
  EXPECT_CONTAINS(withCamera({{"type", "perspective"}, {"perspective", {{"yfov", 0}, {"znear", 1}}}}), "cameras[0].perspective.yfov: expected a number of radians > 0, got 0");
  EXPECT_CONTAINS(withCamera({{"type", "orthographic"}, {"orthographic", {{"xmag", 0}, {"ymag", 1}, {"znear", 0}, {"zfar", 1}}}}),
                  "cameras[0].orthographic.xmag: expected a non-zero number, got 0");
  EXPECT_CONTAINS(withCamera({{"type", "orthographic"}, {"orthographic", {{"xmag", 1}, {"ymag", 1}, {"znear", 2}, {"zfar", 2}}}}),
                  "cameras[0].orthographic.zfar: expected a number > znear (2), got 2");
}

TEST_F(GltfErrors, CyclicOrSharedNodes) {
  {
    GltfBuilder b = quad();
    b.addNode({{"children", {2}}});
    b.addNode({{"children", {1}}});
    EXPECT_CONTAINS(loadError(b), "m.gltf: nodes[1]: is its own ancestor (a cycle in \"children\"); the node hierarchy must be a tree: re-export the file");
  }
  {
    GltfBuilder b = quad();
    b.doc["nodes"][0]["children"] = {0};
    EXPECT_CONTAINS(loadError(b), "m.gltf: nodes[0]: has two parents");
  }
  {
    GltfBuilder b = quad();
    b.addNode({{"children", {0}}});
    b.addNode({{"children", {0}}});
    EXPECT_CONTAINS(loadError(b), "m.gltf: nodes[0]: has two parents (nodes[1] and nodes[2])");
  }
  {
    GltfBuilder b = quad();
    b.addNode({{"children", {0}}});
    b.doc["scenes"][0]["nodes"] = {0, 1};
    EXPECT_CONTAINS(loadError(b), "m.gltf: scenes[0].nodes: nodes[0] is a root of the scene but also a child of nodes[1]");
  }
}

TEST_F(GltfErrors, ExtensionsRequiredThatBrdfclLacks) {
  GltfBuilder b = quad();
  b.useExtension("KHR_texture_transform", true);
  b.useExtension("KHR_texture_basisu", true);
  b.useExtension("EXT_texture_webp", true);
  EXPECT_EQ(loadError(b), scratch.path("m.gltf") + ": extensionsRequired: brdfcl does not support KHR_texture_basisu, EXT_texture_webp; use a version of the model without them (e.g. PNG/JPEG textures instead of KTX2)");
}

TEST_F(GltfErrors, UnknownVariantAndSceneOutOfRange) {
  gltf::LoadOptions o;
  o.variant = "green";
  EXPECT_EQ(loadError(withVariants(), Storage::DataUris, o), scratch.path("m.gltf") + ": --variant 'green' is not a variant of this file; it has: red, blue");
  EXPECT_EQ(loadError(quad(), Storage::DataUris, o), scratch.path("m.gltf") + ": --variant 'green' is not a variant of this file; it has none");
  gltf::LoadOptions s;
  s.scene = 3;
  EXPECT_EQ(loadError(quad(), Storage::DataUris, s), scratch.path("m.gltf") + ": scene 3 is out of range: the file has 1 scene");
}

TEST_F(GltfErrors, TheElementBudgetStopsHugeSceneInstancing) {
  GltfBuilder b = quad();
  gltf::LoadOptions o;
  o.maxElements = 10;  // 4 vertices + 2 triangles per instance
  b.addScene({0});
  EXPECT_NO_THROW(load(b, Storage::DataUris, o));
  b.addMeshNode(0);
  b.doc["scenes"][0]["nodes"] = {0, 1};
  EXPECT_CONTAINS(loadError(b, Storage::DataUris, o), "m.gltf: meshes[0].primitives[0]: the scene has more than 10 vertices and triangles, brdfcl's limit; simplify the model");
}

// The fuzzing seeds must stay valid files: a seed that is refused explores only the error paths.
// Seeds named finding_* are inputs a fuzzer found, kept to reproduce the finding
// (test_fuzz_regressions.cpp); the others are valid files that lead the fuzzer into the loader.
TEST_F(GltfLoader, FuzzSeedsLoad) {
  std::size_t n = 0;
  for (const auto& e : std::filesystem::directory_iterator(std::string(BRDFCL_SOURCE_DIR) + "/tests/fuzz/corpus/gltf")) {
    if (e.path().filename().string().rfind("finding_", 0) == 0) continue;
    SCOPED_TRACE(e.path().string());
    const gltf::Asset a = gltf::load(e.path().string());
    EXPECT_GT(a.primitives.size(), 0u);
    ++n;
  }
  EXPECT_GE(n, 5u);
}

// ---------------------------------------------------------------------------------------------
// The real sample assets

struct AssetCase {
  const char* path;
  std::size_t materials;  // 0 = do not check
  bool textures;
};

TEST(GltfLoaderAssets, EverySampleModelLoads) {
  const AssetCase cases[] = {
      {"SheenChair/glTF/SheenChair.gltf", 0, true},
      {"SheenCloth/glTF/SheenCloth.gltf", 0, true},
      {"ClearCoatTest/glTF-Binary/ClearCoatTest.glb", 0, true},
      {"ClearCoatCarPaint/glTF-Binary/ClearCoatCarPaint.glb", 0, true},
      {"ClearcoatWicker/glTF-Binary/ClearcoatWicker.glb", 0, true},
      {"AnisotropyStrengthTest/glTF-Binary/AnisotropyStrengthTest.glb", 0, true},
      {"AnisotropyRotationTest/glTF-Binary/AnisotropyRotationTest.glb", 0, true},
      {"AnisotropyBarnLamp/glTF/AnisotropyBarnLamp.gltf", 0, true},
      {"MetalRoughSpheresNoTextures/glTF-Binary/MetalRoughSpheresNoTextures.glb", 0, false},
      {"DamagedHelmet/glTF-Binary/DamagedHelmet.glb", 1, true},
      {"WaterBottle/glTF/WaterBottle.gltf", 1, true},
  };
  if (brdfcl::test::assetsDir().empty()) GTEST_SKIP() << brdfcl::test::missingAsset("(any)");
  for (const AssetCase& c : cases) {
    const std::string path = brdfcl::test::assetPath(c.path);
    if (path.empty()) {
      ADD_FAILURE() << brdfcl::test::missingAsset(c.path);
      continue;
    }
    SCOPED_TRACE(c.path);
    const gltf::Asset a = gltf::load(path);
    EXPECT_GT(a.primitives.size(), 0u);
    EXPECT_GT(a.materials.size(), 0u);
    if (c.materials) EXPECT_EQ(a.materials.size(), c.materials);
    EXPECT_EQ(!a.textures.empty(), c.textures);
    for (const gltf::Image& img : a.images) EXPECT_GT(img.rgba.size(), 0u) << img.name;
    for (const gltf::Primitive& p : a.primitives) {
      EXPECT_GT(p.triangleCount(), 0u) << p.where;
      if (p.material >= 0 && a.materials[std::size_t(p.material)].needsTangents() && !p.uv0.empty())
        EXPECT_EQ(p.tangents.size(), 4 * p.vertexCount()) << p.where;
    }
    std::size_t tris = 0;
    for (const auto& p : a.primitives) tris += p.triangleCount();
    std::printf("[asset] %s: %zu primitives, %zu triangles, %zu materials, %zu textures, %zu images, %zu warnings\n", c.path,
                a.primitives.size(), tris, a.materials.size(), a.textures.size(), a.images.size(), a.warnings.size());
    for (const auto& w : a.warnings) std::printf("[asset]   warning: %s\n", w.c_str());
  }
}

TEST(GltfLoaderAssets, SheenChairVariantsAndGeneratedTangents) {
  const char* rel = "SheenChair/glTF/SheenChair.gltf";
  const std::string path = brdfcl::test::assetPath(rel);
  if (path.empty()) GTEST_SKIP() << brdfcl::test::missingAsset(rel);
  const gltf::Asset a = gltf::load(path);
  ASSERT_EQ(a.variants.size(), 2u);
  bool generated = false, transform = false;
  for (const auto& p : a.primitives) generated = generated || p.generatedTangents;
  for (const auto& m : a.materials)
    transform = transform || m.baseColorTexture.transform.scale != std::array<float, 2>{1, 1} ||
                m.normalTexture.transform.scale != std::array<float, 2>{1, 1};
  EXPECT_TRUE(generated);
  EXPECT_TRUE(transform);
  gltf::LoadOptions o;
  o.variant = a.variants[1];
  const gltf::Asset v = gltf::load(path, o);
  ASSERT_EQ(v.primitives.size(), a.primitives.size());
  bool differs = false;
  for (std::size_t i = 0; i < a.primitives.size(); ++i) differs = differs || a.primitives[i].material != v.primitives[i].material;
  EXPECT_TRUE(differs);
  bool mango = false;
  for (const auto& m : a.materials)
    if (std::fabs(m.sheenColorFactor[1] - 0.329f) < 1e-3f && std::fabs(m.sheenRoughnessFactor - 0.8f) < 1e-3f) mango = true;
  EXPECT_TRUE(mango);
}

TEST(GltfLoaderAssets, BarnLampWarnsAndItsKtx2VariantIsRefused) {
  const char* rel = "AnisotropyBarnLamp/glTF/AnisotropyBarnLamp.gltf";
  const std::string path = brdfcl::test::assetPath(rel);
  if (path.empty()) GTEST_SKIP() << brdfcl::test::missingAsset(rel);
  const gltf::Asset a = gltf::load(path);
  ASSERT_EQ(a.warnings.size(), 1u);
  EXPECT_CONTAINS(a.warnings[0], "KHR_materials_transmission");
  EXPECT_CONTAINS(a.warnings[0], "KHR_materials_volume");
  bool aniso = false, emissive = false;
  for (const auto& m : a.materials) {
    aniso = aniso || m.anisotropyTexture.present();
    emissive = emissive || m.emissiveStrength > 1.0f;
  }
  EXPECT_TRUE(aniso);
  EXPECT_TRUE(emissive);
  const std::string ktx = brdfcl::test::assetPath("AnisotropyBarnLamp/glTF-KTX2-Basisu/AnisotropyBarnLamp.gltf");
  if (ktx.empty()) GTEST_SKIP() << brdfcl::test::missingAsset("AnisotropyBarnLamp/glTF-KTX2-Basisu/AnisotropyBarnLamp.gltf");
  EXPECT_EQ(errorOf([&] { gltf::load(ktx); }),
            ktx + ": extensionsRequired: brdfcl does not support KHR_texture_basisu (not listed there, but its textures are KTX2 images without a PNG/JPEG fallback); use a version of the model without them (e.g. PNG/JPEG textures instead of KTX2)");
}

}  // namespace
