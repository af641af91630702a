// What the glTF loader's tests share (test_gltf_loader, test_gltf_tangents, test_gltf_errors,
// test_gltf_loader_assets): the fixture that writes synthetic files from gltf_builder.hpp and loads
// them, a unit quad, a file with material variants, and small vector helpers.
#pragma once

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

// A named namespace, not an anonymous one: the fixtures must be one class in every test file
// (GoogleTest refuses a suite whose fixture differs between translation units).
namespace gltf_loader_test {

inline constexpr double kPi = 3.14159265358979323846;

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
inline const std::vector<float> kQuadP = {0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0};
inline const std::vector<float> kQuadN = {0, 0, 1, 0, 0, 1, 0, 0, 1, 0, 0, 1};
inline const std::vector<float> kQuadUv = {0, 1, 1, 1, 1, 0, 0, 0};
inline const std::vector<std::uint32_t> kQuadI = {0, 1, 2, 0, 2, 3};

inline GltfBuilder quad(json node = json::object(), int material = -1) {
  GltfBuilder b;
  const int mesh = b.addTriangles(kQuadP, kQuadI, material, kQuadN, kQuadUv);
  b.addScene({b.addMeshNode(mesh, node)});
  return b;
}

inline std::array<double, 3> vertex(const std::vector<float>& v, std::size_t i, std::size_t stride = 3) {
  return {v[stride * i], v[stride * i + 1], v[stride * i + 2]};
}

inline double angleDeg(std::array<double, 3> a, std::array<double, 3> b) {
  const double d = a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
  const double la = std::sqrt(a[0] * a[0] + a[1] * a[1] + a[2] * a[2]), lb = std::sqrt(b[0] * b[0] + b[1] * b[1] + b[2] * b[2]);
  return std::acos(std::max(-1.0, std::min(1.0, d / (la * lb)))) * 180.0 / kPi;
}

inline std::array<double, 3> crossD(std::array<double, 3> a, std::array<double, 3> b) {
  return {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]};
}

inline GltfBuilder withVariants() {
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

}  // namespace gltf_loader_test

using namespace gltf_loader_test;
