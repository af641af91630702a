// Tests of EXT_meshopt_compression meshes (GltfMeshopt*), written with libmeshoptimizer's own
// encoders through gltf_builder.hpp: they must load to the mesh they were made from, bit for bit when
// lossless, within the quantization otherwise. KHR_draco_mesh_compression: test_gltf_draco.cpp.
#include "gltf_compression_fixture.hpp"

namespace {

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

}  // namespace
