// Tests of KHR_draco_mesh_compression meshes (GltfDraco*), written with Draco's own encoder: they
// must load to the mesh they were made from, within the quantization, and bad data is one line.
#include "gltf_compression_fixture.hpp"

namespace {

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
