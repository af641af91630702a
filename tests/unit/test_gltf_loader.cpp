// Tests of the glTF loader (host/src/gltf): synthetic files from gltf_builder.hpp for every feature
// (storage kinds, transforms, strips and fans, accessor types, sparse, materials, images, cameras,
// lights, variants) and the fuzzing seeds. Tangents, errors and the sample assets have their own files.
#include "gltf_loader_fixture.hpp"

namespace {

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

}  // namespace
