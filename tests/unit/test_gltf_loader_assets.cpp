// Tests of the glTF loader on the real Khronos sample assets (assets.hpp; skipped when absent): every
// model loads with its materials and textures, the sheen chair's variants, the barn lamp's warnings.
#include "gltf_loader_fixture.hpp"

namespace {

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
