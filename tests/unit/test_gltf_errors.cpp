// Tests of the glTF loader's error messages: one line, the file, the JSON path or object, for
// every structural, range and budget check.
#include "gltf_loader_fixture.hpp"

namespace {

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

}  // namespace
