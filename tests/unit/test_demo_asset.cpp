// Tests of writeDemoAsset (host/src/gltf/demo_asset.cpp), independent of brdfcl's own glTF loader:
// the .glb is read back with tinygltf and by hand, and checked against spheresScene()'s layout,
// camera and lights, the sphere sweep's factors, and the texture formulas restated here.
#include <gtest/gtest.h>

#include <tiny_gltf.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <set>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "host/src/gltf/demo_asset.hpp"
#include "brdfcl/error.hpp"
#include "process.hpp"
#include "support.hpp"

namespace {

using V3 = std::array<double, 3>;
constexpr double kPi = 3.14159265358979323846;

V3 sub(V3 a, V3 b) { return {a[0] - b[0], a[1] - b[1], a[2] - b[2]}; }
double dot(V3 a, V3 b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }
V3 cross(V3 a, V3 b) { return {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]}; }
double length(V3 a) { return std::sqrt(dot(a, a)); }
V3 normalized(V3 a) {
  const double l = length(a);
  return {a[0] / l, a[1] / l, a[2] / l};
}

// Rotates v by the unit quaternion q = (x, y, z, w).
V3 rotate(const std::vector<double>& q, V3 v) {
  if (q.empty()) return v;
  const V3 u{q[0], q[1], q[2]};
  const V3 t = cross(u, v);
  const V3 t2{2 * t[0], 2 * t[1], 2 * t[2]};
  const V3 c = cross(u, t2);
  return {v[0] + q[3] * t2[0] + c[0], v[1] + q[3] * t2[1] + c[1], v[2] + q[3] * t2[2] + c[2]};
}

std::string readFile(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

std::uint32_t u32(const std::string& s, std::size_t at) {
  std::uint32_t v;
  std::memcpy(&v, s.data() + at, 4);
  return v;
}

// Chris Wellons' lowbias32, the hash the generator draws its flakes and brush rings from.
std::uint32_t lowbias32(std::uint32_t x) {
  x ^= x >> 16;
  x *= 0x7feb352du;
  x ^= x >> 15;
  x *= 0x846ca68bu;
  return x ^ (x >> 16);
}

int srgb8(double linear) {
  const double v = std::clamp(linear, 0.0, 1.0);
  return int(std::lround(255.0 * (v <= 0.0031308 ? 12.92 * v : 1.055 * std::pow(v, 1.0 / 2.4) - 0.055)));
}

class DemoAsset : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    scratch_ = new brdfcl::test::ScratchDir("demo-asset");
    path_ = scratch_->path("demo.glb");
    model_ = new tinygltf::Model;
    try {
      brdfcl::gltf::writeDemoAsset(path_);
    } catch (const std::exception& e) {
      loadMessages_ = std::string("writeDemoAsset: ") + e.what();
      return;
    }
    tinygltf::TinyGLTF loader;
    std::string err, warn;
    loaded_ = loader.LoadBinaryFromFile(model_, &err, &warn, path_);
    loadMessages_ = err + warn;
    loadWarnings_ = warn;
  }
  static void TearDownTestSuite() {
    delete model_;
    delete scratch_;
  }
  void SetUp() override { ASSERT_TRUE(loaded_) << loadMessages_; }

  static const tinygltf::Model& model() { return *model_; }

  // The elements of an accessor as doubles, `components` per element.
  static std::vector<double> floats(int accessorIndex, int components) {
    const auto& a = model_->accessors.at(accessorIndex);
    const auto& view = model_->bufferViews.at(a.bufferView);
    const auto& buffer = model_->buffers.at(view.buffer);
    const int stride = a.ByteStride(view);
    std::vector<double> out;
    for (std::size_t i = 0; i < a.count; ++i)
      for (int c = 0; c < components; ++c) {
        const unsigned char* p = buffer.data.data() + view.byteOffset + a.byteOffset + i * stride;
        if (a.componentType == TINYGLTF_COMPONENT_TYPE_FLOAT) {
          float f;
          std::memcpy(&f, p + 4 * c, 4);
          out.push_back(f);
        } else if (a.componentType == TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT) {
          std::uint16_t s;
          std::memcpy(&s, p + 2 * c, 2);
          out.push_back(s);
        } else {
          std::uint32_t s;
          std::memcpy(&s, p + 4 * c, 4);
          out.push_back(s);
        }
      }
    return out;
  }

  // The decoded texels of the image behind texture `t`: 8-bit, `component` per texel.
  static const tinygltf::Image& imageOf(int t) { return model_->images.at(model_->textures.at(t).source); }

  static const tinygltf::Value& extension(const tinygltf::Material& m, const char* name) {
    static const tinygltf::Value none;
    const auto it = m.extensions.find(name);
    return it == m.extensions.end() ? none : it->second;
  }

  static brdfcl::test::ScratchDir* scratch_;
  static std::string path_;
  static tinygltf::Model* model_;
  static bool loaded_;
  static std::string loadMessages_, loadWarnings_;
};

brdfcl::test::ScratchDir* DemoAsset::scratch_ = nullptr;
std::string DemoAsset::path_;
tinygltf::Model* DemoAsset::model_ = nullptr;
bool DemoAsset::loaded_ = false;
std::string DemoAsset::loadMessages_;
std::string DemoAsset::loadWarnings_;

TEST(DemoAssetFile, GlbContainerIsWellFormed) {
  // Its own file: a broken container would also stop tinygltf, and with it the fixture.
  brdfcl::test::ScratchDir scratch("demo-asset-glb");
  brdfcl::gltf::writeDemoAsset(scratch.path("demo.glb"));
  const std::string glb = readFile(scratch.path("demo.glb"));
  ASSERT_GE(glb.size(), 28u);
  EXPECT_EQ(u32(glb, 0), 0x46546C67u);  // "glTF"
  EXPECT_EQ(u32(glb, 4), 2u);
  EXPECT_EQ(u32(glb, 8), glb.size());
  const std::uint32_t jsonLength = u32(glb, 12);
  EXPECT_EQ(u32(glb, 16), 0x4E4F534Au);
  EXPECT_EQ(jsonLength % 4, 0u);
  ASSERT_LE(20 + jsonLength + 8, glb.size());
  const std::uint32_t binLength = u32(glb, 20 + jsonLength);
  EXPECT_EQ(u32(glb, 24 + jsonLength), 0x004E4942u);
  EXPECT_EQ(binLength % 4, 0u);
  EXPECT_EQ(28 + jsonLength + binLength, glb.size());
  const auto gltf = nlohmann::json::parse(glb.substr(20, jsonLength));
  EXPECT_EQ(gltf["asset"]["version"], "2.0");
  const std::set<std::string> used(gltf["extensionsUsed"].begin(), gltf["extensionsUsed"].end());
  EXPECT_EQ(used, (std::set<std::string>{"KHR_materials_sheen", "KHR_materials_clearcoat", "KHR_materials_anisotropy",
                                         "KHR_texture_transform", "KHR_lights_punctual"}));
  EXPECT_FALSE(gltf.contains("extensionsRequired"));
  ASSERT_EQ(gltf["buffers"].size(), 1u);
  EXPECT_FALSE(gltf["buffers"][0].contains("uri"));
  EXPECT_LE(gltf["buffers"][0]["byteLength"].get<std::size_t>(), binLength);
  EXPECT_GT(gltf["buffers"][0]["byteLength"].get<std::size_t>() + 4, binLength);
}

TEST_F(DemoAsset, SpheresHaveTheSweepsLayoutAndFactors) {
  EXPECT_EQ(loadWarnings_, "");
  const auto& m = model();
  ASSERT_EQ(m.materials.size(), 36u);
  ASSERT_EQ(m.scenes.size(), 1u);
  int meshNodes = 0;
  std::set<int> materialsSeen;
  for (int n : m.scenes[0].nodes) {
    const auto& node = m.nodes.at(n);
    if (node.mesh < 0) continue;
    ++meshNodes;
    ASSERT_EQ(node.translation.size(), 3u);
    EXPECT_TRUE(node.rotation.empty() && node.scale.empty() && node.matrix.empty());
    const int col = int(std::lround(node.translation[0] / 1.05 + 2.5)), row = int(std::lround(2.5 - node.translation[1] / 1.05));
    ASSERT_TRUE(row >= 0 && row < 6 && col >= 0 && col < 6) << node.name;
    EXPECT_NEAR(node.translation[0], (col - 2.5) * 1.05, 1e-9);
    EXPECT_NEAR(node.translation[1], (2.5 - row) * 1.05, 1e-9);
    EXPECT_EQ(node.translation[2], 0.0);
    const auto& mesh = m.meshes.at(node.mesh);
    ASSERT_EQ(mesh.primitives.size(), 1u);
    const int mi = mesh.primitives[0].material;
    materialsSeen.insert(mi);
    const auto& mat = m.materials.at(mi);
    const auto& pbr = mat.pbrMetallicRoughness;
    const double t = col / 5.0;
    SCOPED_TRACE(mat.name);
    switch (row) {
      case 0:
      case 1: {
        const auto& sheen = extension(mat, "KHR_materials_sheen");
        ASSERT_TRUE(sheen.IsObject());
        EXPECT_NEAR(sheen.Get("sheenRoughnessFactor").GetNumberAsDouble(), 0.05 + 0.95 * t, 1e-9);
        EXPECT_EQ(sheen.Get("sheenColorFactor").Get(1).GetNumberAsDouble(), row ? 0.45 : 1.0);
        EXPECT_EQ(pbr.roughnessFactor, 0.8);
        EXPECT_EQ(pbr.metallicFactor, 0.0);
        EXPECT_EQ(pbr.baseColorFactor[0], row ? 0.25 : 0.02);
        break;
      }
      case 2: {
        const auto& coat = extension(mat, "KHR_materials_clearcoat");
        ASSERT_TRUE(coat.IsObject());
        EXPECT_EQ(coat.Get("clearcoatFactor").GetNumberAsDouble(), 1.0);
        EXPECT_NEAR(coat.Get("clearcoatRoughnessFactor").GetNumberAsDouble(), t, 1e-9);
        EXPECT_EQ(pbr.roughnessFactor, 0.7);
        break;
      }
      case 3:
      case 4: {
        const auto& aniso = extension(mat, "KHR_materials_anisotropy");
        ASSERT_TRUE(aniso.IsObject());
        EXPECT_NEAR(aniso.Get("anisotropyStrength").GetNumberAsDouble(), row == 3 ? t : 0.8, 1e-9);
        EXPECT_NEAR(aniso.Get("anisotropyRotation").GetNumberAsDouble(), row == 3 ? 0.0 : kPi * t, 1e-9);
        EXPECT_EQ(pbr.metallicFactor, 1.0);
        EXPECT_EQ(pbr.roughnessFactor, 0.3);
        break;
      }
      default:
        EXPECT_TRUE(mat.extensions.empty());
        EXPECT_EQ(pbr.metallicFactor, col % 2 == 0 ? 1.0 : 0.0);
        EXPECT_NEAR(pbr.roughnessFactor, t, 1e-9);
        EXPECT_EQ(pbr.baseColorFactor[1], 0.78);
    }
  }
  EXPECT_EQ(meshNodes, 36);
  EXPECT_EQ(materialsSeen.size(), 36u);
}

TEST_F(DemoAsset, CameraAndLightsMatchTheSpheresScene) {
  const auto& m = model();
  ASSERT_EQ(m.cameras.size(), 1u);
  EXPECT_EQ(m.cameras[0].type, "perspective");
  EXPECT_NEAR(m.cameras[0].perspective.yfov, 30.0 * kPi / 180.0, 1e-9);
  EXPECT_EQ(m.cameras[0].perspective.aspectRatio, 1.0);
  ASSERT_EQ(m.lights.size(), 2u);
  int cameras = 0, key = 0, fill = 0;
  for (int n : m.scenes.at(0).nodes) {
    const auto& node = m.nodes.at(n);
    const V3 position = node.translation.empty() ? V3{0, 0, 0} : V3{node.translation[0], node.translation[1], node.translation[2]};
    // A camera and a directional light look down their node's -Z.
    const V3 forward = rotate(node.rotation, {0, 0, -1});
    if (node.camera >= 0) {
      ++cameras;
      EXPECT_NEAR(length(sub(position, {0, 0, 13})), 0.0, 1e-9);
      EXPECT_NEAR(dot(forward, normalized(sub({0, 0, 0}, position))), 1.0, 1e-9);
      EXPECT_NEAR(rotate(node.rotation, {0, 1, 0})[1], 1.0, 1e-9);
    }
    const auto it = node.extensions.find("KHR_lights_punctual");
    if (it == node.extensions.end()) continue;
    const auto& light = m.lights.at(it->second.Get("light").GetNumberAsInt());
    if (light.type == "directional") {
      ++key;
      EXPECT_NEAR(dot(forward, normalized({0.5, -0.6, -0.62})), 1.0, 1e-9);
      EXPECT_EQ(light.intensity, 2.5);
      EXPECT_EQ(light.color, (std::vector<double>{1.0, 0.96, 0.9}));
    } else {
      ++fill;
      EXPECT_EQ(light.type, "point");
      EXPECT_NEAR(length(sub(position, {-6, 2, 6})), 0.0, 1e-12);
      EXPECT_EQ(light.intensity, 30.0);
      EXPECT_EQ(light.color, (std::vector<double>{0.8, 0.85, 1.0}));
    }
  }
  EXPECT_EQ(cameras, 1);
  EXPECT_EQ(key, 1);
  EXPECT_EQ(fill, 1);
}

TEST_F(DemoAsset, SphereFramesAreUnitOrthogonalAndFollowTheUVs) {
  const auto& m = model();
  const auto& prim = m.meshes.at(0).primitives.at(0);
  for (const auto& mesh : m.meshes) EXPECT_EQ(mesh.primitives.at(0).attributes, prim.attributes);  // shared accessors
  const auto P = floats(prim.attributes.at("POSITION"), 3), N = floats(prim.attributes.at("NORMAL"), 3),
             T = floats(prim.attributes.at("TANGENT"), 4), UV = floats(prim.attributes.at("TEXCOORD_0"), 2),
             I = floats(prim.indices, 1);
  const std::size_t n = P.size() / 3;
  ASSERT_GE(n, 1000u);
  ASSERT_EQ(N.size(), 3 * n);
  ASSERT_EQ(T.size(), 4 * n);
  ASSERT_EQ(UV.size(), 2 * n);
  auto p = [&](std::size_t i) { return V3{P[3 * i], P[3 * i + 1], P[3 * i + 2]}; };
  auto nrm = [&](std::size_t i) { return V3{N[3 * i], N[3 * i + 1], N[3 * i + 2]}; };
  auto tan = [&](std::size_t i) { return V3{T[4 * i], T[4 * i + 1], T[4 * i + 2]}; };
  for (std::size_t i = 0; i < n; ++i) {
    ASSERT_NEAR(length(p(i)), 0.46, 1e-6) << i;
    ASSERT_NEAR(length(nrm(i)), 1.0, 1e-6) << i;
    ASSERT_NEAR(dot(nrm(i), normalized(p(i))), 1.0, 1e-6) << i;
    ASSERT_NEAR(length(tan(i)), 1.0, 1e-6) << i;
    ASSERT_NEAR(dot(tan(i), nrm(i)), 0.0, 1e-6) << i;
    ASSERT_EQ(T[4 * i + 3], 1.0) << i;
    ASSERT_TRUE(UV[2 * i] >= 0 && UV[2 * i] <= 1 && UV[2 * i + 1] >= 0 && UV[2 * i + 1] <= 1) << i;
    // The analytic scene's tangent, Y x N (kernels/gbuffer_spheres.cl), away from the poles.
    const V3 yn = cross({0, 1, 0}, nrm(i));
    if (length(yn) > 0.05) {
      ASSERT_NEAR(dot(tan(i), normalized(yn)), 1.0, 1e-5) << i;
    }
  }
  // v = 0 is the top of the image: the north pole (+Y); u = 0.5 faces the camera (+Z).
  for (std::size_t i = 0; i < n; ++i) {
    if (UV[2 * i + 1] == 0.0) {
      EXPECT_NEAR(p(i)[1], 0.46, 1e-6);
    }
    if (UV[2 * i] == 0.5 && UV[2 * i + 1] == 0.5) {
      EXPECT_NEAR(p(i)[2], 0.46, 1e-6);
    }
  }
  ASSERT_EQ(I.size() % 3, 0u);
  for (std::size_t k = 0; k < I.size(); k += 3) {
    const std::size_t a = std::size_t(I[k]), b = std::size_t(I[k + 1]), c = std::size_t(I[k + 2]);
    ASSERT_TRUE(a < n && b < n && c < n);
    const V3 e1 = sub(p(b), p(a)), e2 = sub(p(c), p(a));
    const double du1 = UV[2 * b] - UV[2 * a], dv1 = UV[2 * b + 1] - UV[2 * a + 1];
    const double du2 = UV[2 * c] - UV[2 * a], dv2 = UV[2 * c + 1] - UV[2 * a + 1];
    const double det = du1 * dv2 - du2 * dv1;
    ASSERT_NE(det, 0.0) << "degenerate UVs in triangle " << k / 3;
    V3 dPdu, dPdv;
    for (int j = 0; j < 3; ++j) {
      dPdu[j] = (e1[j] * dv2 - e2[j] * dv1) / det;
      dPdv[j] = (e2[j] * du1 - e1[j] * du2) / det;
    }
    const V3 nMean = normalized({N[3 * a] + N[3 * b] + N[3 * c], N[3 * a + 1] + N[3 * b + 1] + N[3 * c + 1],
                                 N[3 * a + 2] + N[3 * b + 2] + N[3 * c + 2]});
    const V3 tMean = normalized({T[4 * a] + T[4 * b] + T[4 * c], T[4 * a + 1] + T[4 * b + 1] + T[4 * c + 1],
                                 T[4 * a + 2] + T[4 * b + 2] + T[4 * c + 2]});
    ASSERT_GT(dot(cross(e1, e2), nMean), 0.0) << "triangle " << k / 3 << " faces inwards";
    ASSERT_GT(dot(normalized(dPdu), tMean), 0.99) << "triangle " << k / 3;
    // glTF: bitangent = cross(N, T) * w points to -v (up in the image).
    ASSERT_LT(dot(cross(nMean, tMean), normalized(dPdv)), -0.99) << "triangle " << k / 3;
  }
}

TEST_F(DemoAsset, ClothTextureIsTheWeaveFormula) {
  const auto& m = model();
  int cloth = -1;
  for (const auto& mat : m.materials) {
    const auto& sheen = extension(mat, "KHR_materials_sheen");
    if (!sheen.IsObject()) continue;
    const auto& colour = sheen.Get("sheenColorTexture");
    const auto& rough = sheen.Get("sheenRoughnessTexture");
    ASSERT_TRUE(colour.IsObject() && rough.IsObject()) << mat.name;
    cloth = colour.Get("index").GetNumberAsInt();
    EXPECT_EQ(rough.Get("index").GetNumberAsInt(), cloth);
    for (const auto* info : {&colour, &rough}) {
      const auto& scale = info->Get("extensions").Get("KHR_texture_transform").Get("scale");
      ASSERT_EQ(scale.ArrayLen(), 2u) << mat.name;
      EXPECT_EQ(scale.Get(0).GetNumberAsDouble(), 8.0);
      EXPECT_EQ(scale.Get(1).GetNumberAsDouble(), 4.0);
    }
  }
  ASSERT_GE(cloth, 0);
  const auto& img = imageOf(cloth);
  ASSERT_EQ(img.width, 128);
  ASSERT_EQ(img.height, 128);
  ASSERT_EQ(img.bits, 8);
  ASSERT_GE(img.component, 4);
  const auto& sampler = m.samplers.at(m.textures.at(cloth).sampler);
  EXPECT_EQ(sampler.wrapS, TINYGLTF_TEXTURE_WRAP_REPEAT);
  int gaps = 0, warp = 0, weft = 0;
  for (int y = 0; y < 128; ++y)
    for (int x = 0; x < 128; ++x) {
      // Restated from the design: 4 x 4 threads of pitch 32, threads 0.8 of the pitch wide, the
      // warp (vertical) on top where the thread indices' sum is even.
      const double fx = ((x % 32) + 0.5) / 32 - 0.5, fy = ((y % 32) + 0.5) / 32 - 0.5;
      const bool inWarp = std::fabs(fx) < 0.4, inWeft = std::fabs(fy) < 0.4, warpOnTop = (x / 32 + y / 32) % 2 == 0;
      std::array<double, 3> expected{0.08, 0.08, 0.08};
      int alpha = 128;
      if (inWarp || inWeft) {
        const bool isWarp = inWarp && (warpOnTop || !inWeft);
        const double across = isWarp ? fx : fy, along = isWarp ? fy : fx;
        const double shade = (0.55 + 0.45 * std::cos(kPi / 2 * across / 0.4)) * (0.8 + 0.2 * std::cos(kPi * along));
        const std::array<double, 3> tint = isWarp ? std::array<double, 3>{1, 1, 1} : std::array<double, 3>{0.8, 0.85, 0.95};
        for (int c = 0; c < 3; ++c) expected[c] = tint[c] * shade;
        alpha = 255;
        ++(isWarp ? warp : weft);
      } else {
        ++gaps;
      }
      const unsigned char* texel = &img.image[(std::size_t(y) * 128 + x) * img.component];
      for (int c = 0; c < 3; ++c) ASSERT_NEAR(texel[c], srgb8(expected[c]), 1) << x << "," << y << " channel " << c;
      ASSERT_EQ(texel[3], alpha) << x << "," << y;
    }
  EXPECT_GT(gaps, 0);
  EXPECT_EQ(warp, weft);  // a plain weave shows as much warp as weft
  // The middle of the top thread at the first crossing is near white; the corner gap is dark.
  EXPECT_GE(img.image[(16 * 128 + 16) * img.component], 250);
  EXPECT_LE(img.image[(31 * 128 + 31) * img.component], 90);
}

TEST_F(DemoAsset, FlakeNormalsAreUnitAndTiltedAtMostTwelveDegrees) {
  const auto& m = model();
  int flakes = -1;
  for (const auto& mat : m.materials) {
    const auto& coat = extension(mat, "KHR_materials_clearcoat");
    if (!coat.IsObject()) continue;
    const auto& info = coat.Get("clearcoatNormalTexture");
    ASSERT_TRUE(info.IsObject()) << mat.name;
    flakes = info.Get("index").GetNumberAsInt();
    const auto& scale = info.Get("extensions").Get("KHR_texture_transform").Get("scale");
    ASSERT_EQ(scale.ArrayLen(), 2u);
    EXPECT_EQ(scale.Get(0).GetNumberAsDouble(), 2.0);
    EXPECT_EQ(scale.Get(1).GetNumberAsDouble(), 1.0);
  }
  ASSERT_GE(flakes, 0);
  const auto& img = imageOf(flakes);
  ASSERT_EQ(img.width, 256);
  ASSERT_EQ(img.height, 256);
  ASSERT_GE(img.component, 3);
  auto texel = [&](int x, int y) { return &img.image[(std::size_t(y) * 256 + x) * img.component]; };
  auto decode = [&](int x, int y) {
    const unsigned char* t = texel(x, y);
    return V3{t[0] / 255.0 * 2 - 1, t[1] / 255.0 * 2 - 1, t[2] / 255.0 * 2 - 1};
  };
  const double maxTilt = 12.0 * kPi / 180.0;
  double tiltSum = 0, tiltSquares = 0, largest = 0;
  for (int y = 0; y < 256; ++y)
    for (int x = 0; x < 256; ++x) {
      const V3 nrm = decode(x, y);
      // 8-bit quantization moves each component by at most 1/255.
      ASSERT_NEAR(length(nrm), 1.0, std::sqrt(3.0) / 255) << x << "," << y;
      const double tilt = std::acos(std::min(1.0, nrm[2] / length(nrm)));
      ASSERT_LT(tilt, maxTilt + 0.01) << x << "," << y;
      largest = std::max(largest, tilt);
      // Flakes are 8 x 8 texel cells.
      ASSERT_EQ(std::memcmp(texel(x, y), texel(x - x % 8, y - y % 8), 3), 0) << x << "," << y;
      if (x % 8 == 0 && y % 8 == 0) tiltSum += tilt, tiltSquares += tilt * tilt;
    }
  const double cells = 32 * 32, mean = tiltSum / cells;
  EXPECT_GT(largest, 0.9 * maxTilt);
  EXPECT_GT(std::sqrt(tiltSquares / cells - mean * mean), 0.1 * maxTilt);  // they differ
  // Restated from the design: cell (cx, cy) draws lowbias32(cy * 32 + cx); the low 16 bits give
  // the tilt (sqrt for a uniform disc), the high 16 the azimuth.
  for (const auto& cell : std::vector<std::array<int, 2>>{{0, 0}, {5, 3}, {31, 31}, {17, 29}}) {
    const std::uint32_t h = lowbias32(std::uint32_t(cell[1] * 32 + cell[0]));
    const double tilt = maxTilt * std::sqrt((h & 0xffffu) / 65536.0), azimuth = 2 * kPi * (h >> 16) / 65536.0;
    const V3 expected{std::sin(tilt) * std::cos(azimuth), std::sin(tilt) * std::sin(azimuth), std::cos(tilt)};
    const unsigned char* t = texel(8 * cell[0] + 3, 8 * cell[1] + 5);
    for (int c = 0; c < 3; ++c) EXPECT_NEAR(t[c], std::lround((expected[c] * 0.5 + 0.5) * 255), 1) << cell[0] << "," << cell[1];
  }
}

TEST_F(DemoAsset, BrushedDirectionsAreUnitAndCircular) {
  const auto& m = model();
  int brushed = -1, users = 0;
  for (const auto& mat : m.materials) {
    const auto& aniso = extension(mat, "KHR_materials_anisotropy");
    if (!aniso.IsObject()) continue;
    ++users;
    ASSERT_TRUE(aniso.Get("anisotropyTexture").IsObject()) << mat.name;
    brushed = aniso.Get("anisotropyTexture").Get("index").GetNumberAsInt();
  }
  EXPECT_EQ(users, 12);
  ASSERT_GE(brushed, 0);
  const auto& img = imageOf(brushed);
  ASSERT_EQ(img.width, 256);
  ASSERT_EQ(img.height, 256);
  ASSERT_GE(img.component, 3);
  const auto& sampler = m.samplers.at(m.textures.at(brushed).sampler);
  EXPECT_EQ(sampler.wrapS, TINYGLTF_TEXTURE_WRAP_CLAMP_TO_EDGE);
  for (int y = 0; y < 256; ++y)
    for (int x = 0; x < 256; ++x) {
      const unsigned char* t = &img.image[(std::size_t(y) * 256 + x) * img.component];
      const double dx = t[0] / 255.0 * 2 - 1, dy = t[1] / 255.0 * 2 - 1;
      ASSERT_NEAR(std::hypot(dx, dy), 1.0, std::sqrt(2.0) / 255) << x << "," << y;
      ASSERT_EQ(t[2], 255) << x << "," << y;
      // Tangent to the circle around UV (0.5, 0.5), distances on the sphere (u steps twice as
      // long as v; tangent-space +Y is -v), so perpendicular to the radius, up to the rings' +-4
      // degrees.
      const double a = 2 * ((x + 0.5) / 256 - 0.5), b = -((y + 0.5) / 256 - 0.5), l = std::hypot(a, b);
      ASSERT_NEAR((dx * a + dy * b) / l, 0.0, std::sin(4.0 * kPi / 180) + 0.006) << x << "," << y;
      // Counter-clockwise: +Y on the right of the centre.
      ASSERT_GT((a * dy - b * dx) / l, std::cos(4.0 * kPi / 180) - 0.006) << x << "," << y;
      // Restated from the design: ring floor(128 l) turns by 4 degrees * (2 h / 65535 - 1), h the
      // low 16 bits of lowbias32(ring).
      const double turn = 4.0 * kPi / 180 * (2.0 * (lowbias32(std::uint32_t(l * 128)) & 0xffffu) / 65535.0 - 1);
      const double ex = -b / l * std::cos(turn) - a / l * std::sin(turn), ey = -b / l * std::sin(turn) + a / l * std::cos(turn);
      ASSERT_NEAR(t[0], std::lround((ex * 0.5 + 0.5) * 255), 1) << x << "," << y;
      ASSERT_NEAR(t[1], std::lround((ey * 0.5 + 0.5) * 255), 1) << x << "," << y;
    }
}

TEST(DemoAssetErrors, UnwritablePathThrowsOneLineAndLeavesNoFile) {
  brdfcl::test::ScratchDir scratch("demo-asset-err");
  const std::string missingDir = scratch.path("no/such/dir/demo.glb");
  std::string m = brdfcl::test::errorOf([&] { brdfcl::gltf::writeDemoAsset(missingDir); });
  EXPECT_NE(m.find("no/such/dir/demo.glb"), std::string::npos) << m;
  EXPECT_NE(m.find("No such file or directory"), std::string::npos) << m;
  std::filesystem::create_directory(scratch.path("a-directory.glb"));
  m = brdfcl::test::errorOf([&] { brdfcl::gltf::writeDemoAsset(scratch.path("a-directory.glb")); });
  EXPECT_NE(m.find("a-directory.glb"), std::string::npos) << m;
  { std::ofstream(scratch.path("plain-file")) << "x"; }
  m = brdfcl::test::errorOf([&] { brdfcl::gltf::writeDemoAsset(scratch.path("plain-file/demo.glb")); });
  EXPECT_NE(m.find("plain-file/demo.glb"), std::string::npos) << m;
  // Nothing beyond what the test made: no output, no temporary.
  EXPECT_EQ(scratch.list(), (std::vector<std::string>{"a-directory.glb", "plain-file"}));
  EXPECT_TRUE(std::filesystem::is_empty(scratch.path("a-directory.glb")));
}

TEST(DemoAssetFile, ReplacingAnExistingFileLeavesOnlyTheNewAsset) {
  brdfcl::test::ScratchDir scratch("demo-asset-replace");
  { std::ofstream(scratch.path("demo.glb")) << "old contents"; }
  brdfcl::gltf::writeDemoAsset(scratch.path("demo.glb"));
  EXPECT_EQ(scratch.list(), std::vector<std::string>{"demo.glb"});
  const std::string glb = readFile(scratch.path("demo.glb"));
  ASSERT_GE(glb.size(), 12u);
  EXPECT_EQ(glb.substr(0, 4), "glTF");
  EXPECT_EQ(u32(glb, 8), glb.size());
}

}  // namespace
