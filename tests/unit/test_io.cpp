// Tests of the option spellings (host/src/model/options.cpp) and the materials reader
// (host/src/model/materials.cpp): every accepted form and every error path, with the file name and
// key in each message. Samples and results have their own files (test_io_samples, test_io_results).
#include "io_fixture.hpp"

namespace {

// ---------------------------------------------------------------------------------------------
// Option spellings

TEST_F(Io, OptionSpellingsRoundTrip) {
  using namespace brdfcl;
  for (auto v : {SheenVisibility::Charlie, SheenVisibility::Ashikhmin}) EXPECT_EQ(parseSheenVisibility(toString(v)), v);
  for (auto v : {SheenDistribution::Charlie, SheenDistribution::Ashikhmin})
    EXPECT_EQ(parseSheenDistribution(toString(v)), v);
  for (auto v : {SheenScaling::Min, SheenScaling::View, SheenScaling::None})
    EXPECT_EQ(parseSheenScaling(toString(v)), v);
  for (auto v : {Lobe::All, Lobe::Diffuse, Lobe::Specular, Lobe::Sheen, Lobe::Clearcoat})
    EXPECT_EQ(parseLobe(toString(v)), v);
  EXPECT_STREQ(toString(SheenVisibility::Ashikhmin), "ashikhmin");
  EXPECT_STREQ(toString(SheenDistribution::Charlie), "charlie");
  EXPECT_STREQ(toString(SheenScaling::View), "view");
  EXPECT_STREQ(toString(Lobe::Clearcoat), "clearcoat");
  EXPECT_EQ(parseLobe("specular"), Lobe::Specular);
  EXPECT_EQ(parseSheenScaling("none"), SheenScaling::None);
}

TEST_F(Io, OptionUnknownValuesNameOptionAndChoices) {
  using namespace brdfcl;
  EXPECT_EQ(errorOf([] { parseSheenScaling("foo"); }), "unknown --sheen-scaling value 'foo'; use min, view or none");
  EXPECT_EQ(errorOf([] { parseSheenVisibility("Charlie"); }),
            "unknown --sheen-visibility value 'Charlie'; use charlie or ashikhmin");
  EXPECT_EQ(errorOf([] { parseSheenDistribution(""); }),
            "unknown --sheen-distribution value ''; use charlie or ashikhmin");
  EXPECT_EQ(errorOf([] { parseLobe("base"); }),
            "unknown --lobe value 'base'; use all, diffuse, specular, sheen or clearcoat");
  EXPECT_EQ(errorOf([] { parseLobe("a\nb"); }),
            "unknown --lobe value 'a?b'; use all, diffuse, specular, sheen or clearcoat");
}

// ---------------------------------------------------------------------------------------------
// Materials

const char* kFullGltf = R"({
  "asset": {"version": "2.0"},
  "materials": [
    {
      "name": "velvet",
      "pbrMetallicRoughness": {"baseColorFactor": [0.5, 0.25, 0.125, 0.3], "metallicFactor": 0.0,
                               "roughnessFactor": 0.75},
      "emissiveFactor": [0.75, 0.0, 0.5],
      "extensions": {
        "KHR_materials_sheen": {"sheenColorFactor": [0.9, 0.8, 0.7], "sheenRoughnessFactor": 0.3},
        "KHR_materials_clearcoat": {"clearcoatFactor": 0.6, "clearcoatRoughnessFactor": 0.2},
        "KHR_materials_anisotropy": {"anisotropyStrength": 0.4, "anisotropyRotation": -7.5},
        "KHR_materials_transmission": {"transmissionFactor": 5}
      }
    },
    {}
  ]
})";

TEST_F(Io, MaterialsReadsEveryFactor) {
  std::vector<std::string> warnings;
  const auto ms = brdfcl::parseMaterials(kFullGltf, "m.json", [&](const std::string& w) { warnings.push_back(w); });
  ASSERT_EQ(ms.size(), 2u);
  const MaterialParams& m = ms[0];
  EXPECT_EQ(m.name, "velvet");
  EXPECT_FLOAT_EQ(m.baseColor[0], 0.5f);
  EXPECT_FLOAT_EQ(m.baseColor[1], 0.25f);
  EXPECT_FLOAT_EQ(m.baseColor[2], 0.125f);
  EXPECT_FLOAT_EQ(m.metallic, 0.0f);
  EXPECT_FLOAT_EQ(m.roughness, 0.75f);
  EXPECT_FLOAT_EQ(m.emissive[0], 0.75f);
  EXPECT_FLOAT_EQ(m.emissive[2], 0.5f);
  EXPECT_FALSE(m.draftSheen);
  EXPECT_FLOAT_EQ(m.sheenColor[0], 0.9f);
  EXPECT_FLOAT_EQ(m.sheenColor[1], 0.8f);
  EXPECT_FLOAT_EQ(m.sheenColor[2], 0.7f);
  EXPECT_FLOAT_EQ(m.sheenRoughness, 0.3f);
  EXPECT_FLOAT_EQ(m.clearcoat, 0.6f);
  EXPECT_FLOAT_EQ(m.clearcoatRoughness, 0.2f);
  EXPECT_FLOAT_EQ(m.anisotropyStrength, 0.4f);
  EXPECT_FLOAT_EQ(m.anisotropyRotation, -7.5f);
  // Extensions f leaves out are read past, with one warning naming what is ignored.
  EXPECT_EQ(warnings, std::vector<std::string>{"m.json: materials[0].extensions.KHR_materials_transmission: ignored: "
                                               "brdfcl's f is a reflection BRDF; transmitted light is not modelled"});
}

TEST_F(Io, MaterialsAbsentValuesTakeSpecDefaults) {
  const auto ms =
      brdfcl::parseMaterials(R"({"materials": [{}, {"extensions": {"KHR_materials_sheen": {}}}]})", "m.json");
  ASSERT_EQ(ms.size(), 2u);
  const MaterialParams defaults;
  for (const auto& m : ms) {
    EXPECT_EQ(m.name, "");
    EXPECT_EQ(m.baseColor, (brdfcl::Rgb{1, 1, 1}));
    EXPECT_EQ(m.metallic, 1.0f);
    EXPECT_EQ(m.roughness, 1.0f);
    EXPECT_EQ(m.sheenColor, (brdfcl::Rgb{0, 0, 0}));
    EXPECT_EQ(m.sheenRoughness, 0.0f);
    EXPECT_FALSE(m.draftSheen);
    EXPECT_EQ(m.draftIntensity, defaults.draftIntensity);
    EXPECT_EQ(m.draftColor, defaults.draftColor);
    EXPECT_EQ(m.clearcoat, 0.0f);
    EXPECT_EQ(m.clearcoatRoughness, 0.0f);
    EXPECT_EQ(m.anisotropyStrength, 0.0f);
    EXPECT_EQ(m.anisotropyRotation, 0.0f);
    EXPECT_EQ(m.emissive, (brdfcl::Rgb{0, 0, 0}));
  }
}

TEST_F(Io, MaterialsDraftSheenKeys) {
  const auto ms = brdfcl::parseMaterials(R"({"materials": [
      {"extensions": {"KHR_materials_sheen": {"intensityFactor": 2.5}}},
      {"extensions": {"KHR_materials_sheen": {"colorFactor": [0.1, 0.2, 0.3]}}},
      {"extensions": {"KHR_materials_sheen": {"intensityFactor": 0.5, "colorFactor": [1, 0, 0.5]}}}]})",
                                         "m.json");
  ASSERT_EQ(ms.size(), 3u);
  EXPECT_TRUE(ms[0].draftSheen);
  EXPECT_FLOAT_EQ(ms[0].draftIntensity, 2.5f);
  EXPECT_EQ(ms[0].draftColor, (brdfcl::Rgb{1, 1, 1}));
  EXPECT_TRUE(ms[1].draftSheen);
  EXPECT_FLOAT_EQ(ms[1].draftIntensity, 1.0f);
  EXPECT_FLOAT_EQ(ms[1].draftColor[2], 0.3f);
  EXPECT_TRUE(ms[2].draftSheen);
  EXPECT_FLOAT_EQ(ms[2].draftIntensity, 0.5f);
  EXPECT_EQ(ms[2].draftColor, (brdfcl::Rgb{1, 0, 0.5f}));
  // Draft materials leave the ratified fields at their defaults.
  EXPECT_EQ(ms[2].sheenColor, (brdfcl::Rgb{0, 0, 0}));
}

TEST_F(Io, MaterialsMixedSheenFamiliesRejected) {
  const std::string m = errorOf([] {
    brdfcl::parseMaterials(
        R"({"materials": [{}, {"extensions": {"KHR_materials_sheen": {"intensityFactor": 1, "sheenRoughnessFactor": 0.5}}}]})",
        "m.json");
  });
  EXPECT_CONTAINS(m, "m.json: materials[1].extensions.KHR_materials_sheen: mixes draft keys (intensityFactor)");
  EXPECT_CONTAINS(m, "ratified keys (sheenRoughnessFactor)");
}

TEST_F(Io, MaterialsTextureReferencesWarnOncePerMaterial) {
  std::vector<std::string> warnings;
  const auto ms = brdfcl::parseMaterials(R"({"materials": [
      {"name": "plain"},
      {"name": "velvet", "normalTexture": {"index": 0},
       "pbrMetallicRoughness": {"baseColorTexture": {"index": 1}, "metallicRoughnessTexture": {"index": 2}},
       "extensions": {"KHR_materials_sheen": {"sheenColorTexture": {"index": 3}, "sheenColorFactor": [1, 1, 1]},
                      "KHR_materials_clearcoat": {"clearcoatNormalTexture": {"index": 4}},
                      "KHR_materials_anisotropy": {"anisotropyTexture": {"index": 5}}}},
      {"occlusionTexture": {"index": 0}},
      {"extensions": {"KHR_materials_sheen": {"colorIntensityTexture": {"index": 0}, "intensityFactor": 1}}},
      {"emissiveTexture": {"index": 0}, "extensions": {"KHR_materials_clearcoat": {"clearcoatTexture": {}, "clearcoatRoughnessTexture": {}}}},
      {"extensions": {"KHR_materials_sheen": {"sheenRoughnessTexture": {"index": 0}}}}]})",
                                         "m.json", [&](const std::string& w) { warnings.push_back(w); });
  ASSERT_EQ(ms.size(), 6u);
  ASSERT_EQ(warnings.size(), 5u);
  EXPECT_CONTAINS(warnings[0], "m.json: materials[1] ('velvet'): texture references are ignored");
  EXPECT_CONTAINS(warnings[0], "using factors only");
  for (const char* key : {"normalTexture", "baseColorTexture", "metallicRoughnessTexture", "sheenColorTexture",
                          "clearcoatNormalTexture", "anisotropyTexture"})
    EXPECT_CONTAINS(warnings[0], key);
  EXPECT_CONTAINS(warnings[1], "m.json: materials[2]: texture references are ignored (occlusionTexture)");
  EXPECT_CONTAINS(warnings[2], "materials[3]: texture references are ignored (colorIntensityTexture)");
  EXPECT_CONTAINS(warnings[3], "emissiveTexture, clearcoatTexture, clearcoatRoughnessTexture");
  EXPECT_CONTAINS(warnings[4], "materials[5]: texture references are ignored (sheenRoughnessTexture)");
  EXPECT_EQ(ms[1].sheenColor, (brdfcl::Rgb{1, 1, 1}));
  // No callback: textures are still ignored without complaint.
  EXPECT_NO_THROW(brdfcl::parseMaterials(R"({"materials": [{"normalTexture": {"index": 0}}]})", "m.json"));
}

struct BadMaterial {
  const char* json;
  const char* expected;  // a substring of the message, after "m.json: "
};

TEST_F(Io, MaterialsValidationErrorsNameFileAndKey) {
  const BadMaterial cases[] = {
      {R"({"materials": [{}, {}, {"pbrMetallicRoughness": {"roughnessFactor": 1.5}}]})",
       "materials[2].pbrMetallicRoughness.roughnessFactor: expected a number in [0, 1], got 1.5"},
      {R"({"materials": [{"pbrMetallicRoughness": {"metallicFactor": -0.1}}]})",
       "materials[0].pbrMetallicRoughness.metallicFactor: expected a number in [0, 1], got -0.1"},
      {R"({"materials": [{"pbrMetallicRoughness": {"metallicFactor": "0.5"}}]})",
       "materials[0].pbrMetallicRoughness.metallicFactor: expected a number in [0, 1], got string \"0.5\""},
      {R"({"materials": [{"pbrMetallicRoughness": {"metallicFactor": true}}]})",
       "metallicFactor: expected a number in [0, 1], got true"},
      {R"({"materials": [{"pbrMetallicRoughness": {"metallicFactor": null}}]})",
       "metallicFactor: expected a number in [0, 1], got null"},
      {R"({"materials": [{"pbrMetallicRoughness": {"roughnessFactor": 1e999}}]})",
       "invalid JSON: number overflow parsing '1e999' at line 1; numbers must be finite"},
      {R"({"materials": [{"pbrMetallicRoughness": {"baseColorFactor": [1, 1, 1]}}]})",
       "materials[0].pbrMetallicRoughness.baseColorFactor: expected an array of 4 numbers in [0, 1], got an array of 3 "
       "elements"},
      {R"({"materials": [{"pbrMetallicRoughness": {"baseColorFactor": [1, 1, 1, 1, 1]}}]})",
       "baseColorFactor: expected an array of 4 numbers in [0, 1], got an array of 5 elements"},
      {R"({"materials": [{"pbrMetallicRoughness": {"baseColorFactor": {"r": 1}}}]})",
       "baseColorFactor: expected an array of 4 numbers in [0, 1], got an object"},
      {R"({"materials": [{"pbrMetallicRoughness": {"baseColorFactor": [1, 2, 1, 1]}}]})",
       "materials[0].pbrMetallicRoughness.baseColorFactor[1]: expected a number in [0, 1], got 2"},
      {R"({"materials": [{"pbrMetallicRoughness": {"baseColorFactor": [1, 1, 1, 1.01]}}]})",
       "baseColorFactor[3]: expected a number in [0, 1], got 1.01"},
      {R"({"materials": [{"pbrMetallicRoughness": {"baseColorFactor": [1, "x", 1, 1]}}]})",
       "baseColorFactor[1]: expected a number in [0, 1], got string \"x\""},
      {R"({"materials": [{"emissiveFactor": [0, -1, 0]}]})",
       "materials[0].emissiveFactor[1]: expected a number >= 0, got -1"},
      {R"({"materials": [{"emissiveFactor": [0, 0]}]})",
       "materials[0].emissiveFactor: expected an array of 3 numbers >= 0, got an array of 2 elements"},
      {"{\"materials\": [\n{\"emissiveFactor\": [0, 0, 1e999]}]}",
       "invalid JSON: number overflow parsing '1e999' at line 2"},
      {R"({"materials": [{"emissiveFactor": [0, 0, 1e300]}]})",
       "emissiveFactor[2]: expected a number >= 0, got 1e+300 (too large for float)"},
      {R"({"materials": [{"name": 7}]})", "materials[0].name: expected a string, got 7"},
      {R"({"materials": [{"pbrMetallicRoughness": [1]}]})",
       "materials[0].pbrMetallicRoughness: expected an object, got an array of 1 element"},
      {R"({"materials": [{"extensions": 3}]})", "materials[0].extensions: expected an object, got 3"},
      {R"({"materials": [{"extensions": {"KHR_materials_clearcoat": "yes"}}]})",
       "materials[0].extensions.KHR_materials_clearcoat: expected an object, got string \"yes\""},
      {R"({"materials": [{"extensions": {"KHR_materials_sheen": {"sheenColorFactor": [0.5, 0.5, 1.5]}}}]})",
       "materials[0].extensions.KHR_materials_sheen.sheenColorFactor[2]: expected a number in [0, 1], got 1.5"},
      {R"({"materials": [{"extensions": {"KHR_materials_sheen": {"sheenColorFactor": [0.5, 0.5, 0.5, 1]}}}]})",
       "sheenColorFactor: expected an array of 3 numbers in [0, 1], got an array of 4 elements"},
      {R"({"materials": [{"extensions": {"KHR_materials_sheen": {"sheenRoughnessFactor": 2}}}]})",
       "KHR_materials_sheen.sheenRoughnessFactor: expected a number in [0, 1], got 2"},
      {R"({"materials": [{"extensions": {"KHR_materials_sheen": {"intensityFactor": -1}}}]})",
       "materials[0].extensions.KHR_materials_sheen.intensityFactor: expected a number >= 0, got -1"},
      {R"({"materials": [{"extensions": {"KHR_materials_sheen": {"colorFactor": [0, 1.5, 0]}}}]})",
       "KHR_materials_sheen.colorFactor[1]: expected a number in [0, 1], got 1.5"},
      {R"({"materials": [{"extensions": {"KHR_materials_clearcoat": {"clearcoatFactor": 1.5}}}]})",
       "materials[0].extensions.KHR_materials_clearcoat.clearcoatFactor: expected a number in [0, 1], got 1.5"},
      {R"({"materials": [{"extensions": {"KHR_materials_clearcoat": {"clearcoatRoughnessFactor": -2}}}]})",
       "KHR_materials_clearcoat.clearcoatRoughnessFactor: expected a number in [0, 1], got -2"},
      {R"({"materials": [{"extensions": {"KHR_materials_anisotropy": {"anisotropyStrength": 1.1}}}]})",
       "KHR_materials_anisotropy.anisotropyStrength: expected a number in [0, 1], got 1.1"},
      {R"({"materials": [{"extensions": {"KHR_materials_anisotropy": {"anisotropyRotation": "90deg"}}}]})",
       "KHR_materials_anisotropy.anisotropyRotation: expected a finite number, got string \"90deg\""},
      {R"({"materials": [{"extensions": {"KHR_materials_anisotropy": {"anisotropyRotation": -1e999}}}]})",
       "invalid JSON: number overflow parsing '-1e999' at line 1"},
      {R"({"materials": [5]})", "materials[0]: expected a material object, got 5"},
      {R"({"materials": {}})", "materials: expected an array of material objects, got an object"},
      {R"({"materials": []})", "materials: the array is empty"},
      {R"({"meshes": []})", "no \"materials\" array at the top level"},
      {R"([{"name": "x"}])",
       "expected a JSON object with a \"materials\" array at the top level, got an array of 1 element"},
      {R"("materials")", "expected a JSON object"},
      {"{\"materials\": [\n{\"name\": \"a\",}\n]}", "invalid JSON: parse error at line 2, column"},
      {"", "invalid JSON"},
      {"{\"materials\": [", "invalid JSON"},
  };
  for (const auto& c : cases) {
    SCOPED_TRACE(c.json);
    const std::string m = errorOf([&] { brdfcl::parseMaterials(c.json, "m.json"); });
    EXPECT_EQ(m.rfind("m.json: ", 0), 0u) << m;
    EXPECT_CONTAINS(m, c.expected);
  }
}

TEST_F(Io, MaterialsExactMessageForOutOfRangeRoughness) {
  EXPECT_EQ(errorOf([] {
              brdfcl::parseMaterials(R"({"materials": [{}, {}, {"pbrMetallicRoughness": {"roughnessFactor": 1.5}}]})",
                                     "m.json");
            }),
            "m.json: materials[2].pbrMetallicRoughness.roughnessFactor: expected a number in [0, 1], got 1.5");
}

TEST_F(Io, MaterialsAcceptBoundaryValues) {
  const auto ms = brdfcl::parseMaterials(
      R"({"materials": [{"pbrMetallicRoughness": {"baseColorFactor": [0, 1, 0, 1], "metallicFactor": 1, "roughnessFactor": 0},
          "emissiveFactor": [0, 1000, 0],
          "extensions": {"KHR_materials_anisotropy": {"anisotropyStrength": 1, "anisotropyRotation": 1000},
                         "KHR_materials_sheen": {"intensityFactor": 0}}}]})",
      "m.json");
  EXPECT_EQ(ms[0].roughness, 0.0f);
  EXPECT_EQ(ms[0].emissive[1], 1.0f);  // above the schema's [0, 1]: clamped (test_emissive_factor.cpp)
  EXPECT_EQ(ms[0].anisotropyRotation, 1000.0f);
  EXPECT_TRUE(ms[0].draftSheen);
  EXPECT_EQ(ms[0].draftIntensity, 0.0f);
}

TEST_F(Io, ReadMaterialsFromFile) {
  const std::string p = write("scene.gltf", kFullGltf);
  const auto ms = brdfcl::readMaterials(p);
  ASSERT_EQ(ms.size(), 2u);
  EXPECT_EQ(ms[0].name, "velvet");

  const std::string bad = write("bad.json", R"({"materials": [{"pbrMetallicRoughness": {"roughnessFactor": 2}}]})");
  EXPECT_EQ(errorOf([&] { brdfcl::readMaterials(bad); }),
            bad + ": materials[0].pbrMetallicRoughness.roughnessFactor: expected a number in [0, 1], got 2");
}

TEST_F(Io, ReadMaterialsUnreadableFile) {
  const std::string missing = path("x.json");
  EXPECT_EQ(errorOf([&] { brdfcl::readMaterials(missing); }),
            "cannot read materials file '" + missing + "': No such file or directory");
  EXPECT_EQ(errorOf([&] { brdfcl::readMaterials(dir_.string()); }),
            "cannot read materials file '" + dir_.string() + "': Is a directory");
}

}  // namespace

// 001's own velvet example spells the intensity "sheenFactor": it must read as the draft.
TEST_F(Io, DraftSheenFactorExampleIsTheDraft) {
  const auto m = brdfcl::parseMaterials(
      R"({"materials":[{"name":"velvet","extensions":{"KHR_materials_sheen":{"sheenFactor":0.5}}}]})", "draft.json");
  ASSERT_EQ(m.size(), 1u);
  EXPECT_TRUE(m[0].draftSheen);
  EXPECT_FLOAT_EQ(m[0].draftIntensity, 0.5f);
  EXPECT_THROW(brdfcl::parseMaterials(
                   R"({"materials":[{"extensions":{"KHR_materials_sheen":{"sheenFactor":1,"intensityFactor":1}}}]})",
                   "both.json"),
               brdfcl::Error);
}
