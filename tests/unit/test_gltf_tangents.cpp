// Tests of the glTF loader's tangent generation (host/src/gltf/tangents.cpp) against analytic
// tangents of a UV sphere, mirrored and degenerate UVs, and the anisotropy assets.
#include "gltf_loader_fixture.hpp"

namespace {

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

}  // namespace
