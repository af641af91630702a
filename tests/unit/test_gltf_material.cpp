// The one glTF material reader (model/gltf_material.hpp) behind the materials file and the glTF
// loader: one material object gives the same factors through both, the schema's checks hold in
// both (name a string; alphaMode, alphaCutoff, doubleSided), and checkMaterial uses its ranges.
#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "brdfcl/error.hpp"
#include "brdfcl/gltf.hpp"
#include "brdfcl/io.hpp"
#include "gltf_builder.hpp"
#include "host/src/model/pack.hpp"
#include "process.hpp"
#include "support.hpp"

namespace {

using brdfcl::test::errorOf;
using brdfcl::test::quadWithMaterial;
using brdfcl::test::ScratchDir;
using brdfcl::test::writeFile;
using json = nlohmann::json;

const json kMaterial = json::parse(R"({
  "name": "all",
  "pbrMetallicRoughness": {"baseColorFactor": [0.25, 0.5, 0.75, 0.5], "metallicFactor": 0.125,
                           "roughnessFactor": 0.375},
  "emissiveFactor": [0.5, 0.25, 1],
  "alphaMode": "MASK", "alphaCutoff": 0.25, "doubleSided": true,
  "extensions": {
    "KHR_materials_sheen": {"sheenColorFactor": [0.5, 0.5, 0.25], "sheenRoughnessFactor": 0.625},
    "KHR_materials_clearcoat": {"clearcoatFactor": 0.875, "clearcoatRoughnessFactor": 0.0625},
    "KHR_materials_anisotropy": {"anisotropyStrength": 0.5, "anisotropyRotation": 1.25}
  }
})");

class GltfMaterialReader : public ::testing::Test {
 protected:
  ScratchDir dir_{"gltf-material"};
  std::string materialsFile(const json& material) const {
    const std::string p = dir_.path("m.json");
    writeFile(p, json{{"materials", json::array({material})}}.dump());
    return p;
  }
  std::string asset(const json& material) const { return quadWithMaterial(material).write(dir_.dir(), "a.gltf"); }
};

TEST_F(GltfMaterialReader, BothReadersGiveTheSameFactors) {
  const auto fromFile = brdfcl::readMaterials(materialsFile(kMaterial), {{}, false});
  const brdfcl::gltf::Asset a = brdfcl::gltf::load(asset(kMaterial));
  ASSERT_EQ(fromFile.size(), 1u);
  ASSERT_EQ(a.materials.size(), 1u);
  const brdfcl::MaterialParams& f = fromFile[0];
  const brdfcl::gltf::Material& g = a.materials[0];
  EXPECT_EQ(f.name, g.name);
  EXPECT_EQ(g.baseColorFactor, (std::array<float, 4>{0.25f, 0.5f, 0.75f, 0.5f}));
  for (int c = 0; c < 3; ++c) {
    EXPECT_EQ(f.baseColor[c], g.baseColorFactor[c]);
    EXPECT_EQ(f.emissive[c], g.emissiveFactor[c]);
    EXPECT_EQ(f.sheenColor[c], g.sheenColorFactor[c]);
  }
  EXPECT_EQ(f.metallic, g.metallicFactor);
  EXPECT_EQ(f.roughness, g.roughnessFactor);
  EXPECT_EQ(f.sheenRoughness, g.sheenRoughnessFactor);
  EXPECT_EQ(f.clearcoat, g.clearcoatFactor);
  EXPECT_EQ(f.clearcoatRoughness, g.clearcoatRoughnessFactor);
  EXPECT_EQ(f.anisotropyStrength, g.anisotropyStrength);
  EXPECT_EQ(f.anisotropyRotation, g.anisotropyRotation);
  EXPECT_TRUE(f.anisotropyExtension);
  EXPECT_EQ(g.alphaMode, brdfcl::gltf::AlphaMode::Mask);
  EXPECT_EQ(g.alphaCutoff, 0.25f);
  EXPECT_TRUE(g.doubleSided);
}

TEST_F(GltfMaterialReader, ANameThatIsNotAStringIsRefusedByBoth) {
  const json m = {{"name", 5}};
  const std::string file = materialsFile(m);
  EXPECT_EQ(errorOf([&] { brdfcl::readMaterials(file, {{}, false}); }),
            file + ": materials[0].name: expected a string, got 5");
  const std::string gltf = asset(m);
  EXPECT_EQ(errorOf([&] { brdfcl::gltf::load(gltf); }), gltf + ": materials[0].name: expected a string, got 5");
}

TEST_F(GltfMaterialReader, AlphaModeCutoffAndDoubleSidedAreCheckedByBoth) {
  const std::vector<std::pair<json, std::string>> cases = {
      {{{"alphaMode", "SOMETIMES"}}, "materials[0].alphaMode: expected \"OPAQUE\", \"MASK\" or \"BLEND\", got string \"SOMETIMES\""},
      {{{"alphaCutoff", -1}}, "materials[0].alphaCutoff: expected a number >= 0, got -1"},
      {{{"doubleSided", "yes"}}, "materials[0].doubleSided: expected true or false, got string \"yes\""},
  };
  for (const auto& [m, message] : cases) {
    const std::string file = materialsFile(m);
    EXPECT_EQ(errorOf([&] { brdfcl::readMaterials(file, {{}, false}); }), file + ": " + message) << m.dump();
    const std::string gltf = asset(m);
    EXPECT_EQ(errorOf([&] { brdfcl::gltf::load(gltf); }), gltf + ": " + message) << m.dump();
  }
}

TEST_F(GltfMaterialReader, CheckMaterialNamesTheFieldWithTheReadersRange) {
  brdfcl::MaterialParams m;
  m.clearcoatRoughness = 1.5f;
  EXPECT_EQ(errorOf([&] { brdfcl::checkMaterial(m, 2); }), "material 2: clearcoatRoughness must be a number in [0, 1], got 1.5");
  m = {};
  m.emissive[1] = -0.5f;
  EXPECT_EQ(errorOf([&] { brdfcl::checkMaterial(m, 0); }), "material 0: emissive[1] must be a number >= 0, got -0.5");
  m = {};
  m.ior = 0.5f;
  EXPECT_EQ(errorOf([&] { brdfcl::checkMaterial(m, 1); }), "material 1: ior must be 0 or a number >= 1, got 0.5");
  m = {};
  m.draftIntensity = 1e31f;
  EXPECT_EQ(errorOf([&] { brdfcl::checkMaterial(m, 0); }),
            "material 0: draftIntensity must be a number >= 0, got 1e+31 (at most 1e+30: f would overflow float)");
  m = {};
  m.baseColor[2] = std::nanf("");
  EXPECT_EQ(errorOf([&] { brdfcl::checkMaterial(m, 3); }), "material 3: baseColor[2] must be a number in [0, 1], got nan");
  EXPECT_NO_THROW(brdfcl::checkMaterial(brdfcl::MaterialParams{}, 0));
}

}  // namespace
