// Tests of the file I/O (host/src/io) and the option spellings (host/src/model/options.cpp):
// every accepted form and every error path, with the file name and line/row/key in each message.
// Each test works in its own temporary directory, removed afterwards.
#include <gtest/gtest.h>
#include <sys/resource.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <csignal>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <functional>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include "support.hpp"
#include "brdfcl/error.hpp"
#include "brdfcl/io.hpp"
#include "brdfcl/material.hpp"

namespace fs = std::filesystem;
using brdfcl::Error;
using brdfcl::test::errorOf;
using brdfcl::MaterialParams;
using brdfcl::Samples;

namespace {

std::atomic<int> dirCounter{0};

class Io : public ::testing::Test {
 protected:
  void SetUp() override {
    const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
    dir_ = fs::temp_directory_path() /
           ("brdfcl-io-" + std::to_string(::getpid()) + "-" + info->name() + "-" + std::to_string(dirCounter++));
    fs::remove_all(dir_);
    fs::create_directories(dir_);
  }
  void TearDown() override {
    std::error_code ec;
    fs::remove_all(dir_, ec);
  }

  std::string path(const std::string& name) const { return (dir_ / name).string(); }

  std::string write(const std::string& name, const std::string& content) const {
    const std::string p = path(name);
    std::ofstream(p, std::ios::binary) << content;
    return p;
  }

  std::vector<std::string> listDir() const {
    std::vector<std::string> names;
    for (const auto& e : fs::directory_iterator(dir_)) names.push_back(e.path().filename().string());
    return names;
  }

  fs::path dir_;
};


std::string readFile(const std::string& p) {
  std::ifstream in(p, std::ios::binary);
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

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

// ---------------------------------------------------------------------------------------------
// Samples: CSV

TEST_F(Io, CsvReadsAndNormalizes) {
  const std::string p = write("s.csv",
                              "\xEF\xBB\xBFmaterial, Lx ,Ly,Lz,Vx,Vy,Vz\r\n"
                              "0,0,0,2,1,0,1\r\n"
                              " 2 , 3 ,\t4, 0 ,0,-5,0\r\n"
                              "1.0,+1e-300,0,0,1e300,1e300,0\r\n"
                              "\r\n\n  \n");
  const Samples s = brdfcl::readSamples(p, 3, false);
  ASSERT_EQ(s.size(), 3u);
  EXPECT_EQ(s.material, (std::vector<std::uint32_t>{0, 2, 1}));
  const float h = static_cast<float>(1.0 / std::sqrt(2.0));
  const std::vector<float> L = {0, 0, 1, 0.6f, 0.8f, 0, 1, 0, 0};
  const std::vector<float> V = {h, 0, h, 0, -1, 0, h, h, 0};
  ASSERT_EQ(s.L.size(), L.size());
  for (std::size_t i = 0; i < L.size(); ++i) {
    EXPECT_FLOAT_EQ(s.L[i], L[i]) << i;
    EXPECT_FLOAT_EQ(s.V[i], V[i]) << i;
  }
}

TEST_F(Io, CsvQuotedHeaderNames) {
  const std::string p = write("q.csv", "\"material\",\"Lx\",\"Ly\",\"Lz\",\"Vx\",\"Vy\",\"Vz\"\n0,0,0,1,0,0,1\n");
  EXPECT_EQ(brdfcl::readSamples(p, 1, false).size(), 1u);
  const std::string half = write("h.csv", "\"material,Lx,Ly,Lz,Vx,Vy,Vz\n0,0,0,1,0,0,1\n");
  EXPECT_CONTAINS(errorOf([&] { brdfcl::readSamples(half, 1, false); }),
                  half + ": header: unknown column '\"material' (column 1); did you mean material?");
}

TEST_F(Io, CsvWithoutTrailingNewlineAndWithoutMaterialCheck) {
  const std::string p = write("s.csv", "material,Lx,Ly,Lz,Vx,Vy,Vz\n123,0,0,1,0,0,1");
  const Samples s = brdfcl::readSamples(p, 0, false);
  ASSERT_EQ(s.size(), 1u);
  EXPECT_EQ(s.material[0], 123u);
}

TEST_F(Io, CsvMaterialColumnOptional) {
  const std::string grid = write("g.csv", "Lx,Ly,Lz,Vx,Vy,Vz\n0,0,1,0,0,1\n1,0,1,0,1,1\n");
  const Samples s = brdfcl::readSamples(grid, 2, true);
  EXPECT_EQ(s.size(), 2u);
  EXPECT_TRUE(s.material.empty());

  // Without the option the material column is required.
  const std::string m = errorOf([&] { brdfcl::readSamples(grid, 2, false); });
  EXPECT_CONTAINS(m, grid + ": header: missing column material; add it, or pass --grid");

  // With the option and a material column, indices are read and still range-checked.
  const std::string withMat = write("m.csv", "material,Lx,Ly,Lz,Vx,Vy,Vz\n1,0,0,1,0,0,1\n");
  EXPECT_EQ(brdfcl::readSamples(withMat, 2, true).material, (std::vector<std::uint32_t>{1}));
  EXPECT_EQ(errorOf([&] { brdfcl::readSamples(withMat, 1, true); }),
            withMat + ":2: material index 1 out of range (1 material)");

  // Rows of a 6-column file must have 6 fields.
  const std::string short6 = write("s6.csv", "Lx,Ly,Lz,Vx,Vy,Vz\n0,0,1,0,0,1,1\n");
  EXPECT_EQ(errorOf([&] { brdfcl::readSamples(short6, 0, true); }),
            short6 + ":2: expected 6 fields (Lx,Ly,Lz,Vx,Vy,Vz), got 7");
}

struct BadCsv {
  const char* body;      // lines after the header
  const char* expected;  // message after "<path>:"
};

TEST_F(Io, CsvRowErrorsNameFileLineAndField) {
  const BadCsv cases[] = {
      {"0,0,0,1,0,0,1\n0,0,0,1,0,0,1\n0,0,1,0,0\n", "4: expected 7 fields (material,Lx,Ly,Lz,Vx,Vy,Vz), got 5"},
      {"0,0,0,1,0,0,1,5\n", "2: expected 7 fields (material,Lx,Ly,Lz,Vx,Vy,Vz), got 8"},
      {"0,0,0,1,0,0,1,\n", "2: expected 7 fields (material,Lx,Ly,Lz,Vx,Vy,Vz), got 8"},
      {"0,0,0,1,0,abc,1\n", "2: field 'Vy' is not a number: 'abc'"},
      {"0,0,0,1,0,,1\n", "2: field 'Vy' is not a number: ''"},
      {"0,0,0,1,0,1 2,1\n", "2: field 'Vy' is not a number: '1 2'"},
      {"0,0x1,0,1,0,0,1\n", "2: field 'Lx' is not a number: '0x1'"},
      {"0,1.5.2,0,1,0,0,1\n", "2: field 'Lx' is not a number: '1.5.2'"},
      {"0,++1,0,1,0,0,1\n", "2: field 'Lx' is not a number: '++1'"},
      {"x,0,0,1,0,0,1\n", "2: field 'material' is not a number: 'x'"},
      {"0,0,0,1,0,0,nan\n", "2: field 'Vz' is not finite: 'nan'"},
      {"0,inf,0,1,0,0,1\n", "2: field 'Lx' is not finite: 'inf'"},
      {"0,0,-1e999,1,0,0,1\n", "2: field 'Ly' is not finite: '-1e999'"},
      {"3.5,0,0,1,0,0,1\n", "2: material index 3.5 is not a non-negative integer"},
      {"-1,0,0,1,0,0,1\n", "2: material index -1 is not a non-negative integer"},
      {"0,0,0,1,0,0,1\n12,0,0,1,0,0,1\n", "3: material index 12 out of range (3 materials)"},
      {"3,0,0,1,0,0,1\n", "2: material index 3 out of range (3 materials)"},
      {"0,0,0,1,0,0,1\n0,0,0,1,0,0,1\n0,0,0,1,0,0,1\n1,0,0,0,0,0,1\n", "5: L has zero length"},
      {"1,0,0,1,-0,0,0\n", "2: V has zero length"},
      {"1,1e-400,0,0,0,0,1\n", "2: L has zero length"},
      {"0,0,0,1,0,0,1\n\n0,0,0,1,0,0,1\n", "3: empty line; expected 7 fields (material,Lx,Ly,Lz,Vx,Vy,Vz)"},
  };
  for (const auto& c : cases) {
    SCOPED_TRACE(c.body);
    const std::string p = write("s.csv", std::string("material,Lx,Ly,Lz,Vx,Vy,Vz\n") + c.body);
    EXPECT_EQ(errorOf([&] { brdfcl::readSamples(p, 3, false); }), p + ":" + c.expected);
  }
}

TEST_F(Io, CsvMaterialIndexForms) {
  const std::string p =
      write("s.csv", "material,Lx,Ly,Lz,Vx,Vy,Vz\n3.0,0,0,1,0,0,1\n2e0,0,0,1,0,0,1\n-0,0,0,1,0,0,1\n");
  EXPECT_EQ(brdfcl::readSamples(p, 4, false).material, (std::vector<std::uint32_t>{3, 2, 0}));
  const std::string huge = write("h.csv", "material,Lx,Ly,Lz,Vx,Vy,Vz\n1e10,0,0,1,0,0,1\n");
  EXPECT_EQ(errorOf([&] { brdfcl::readSamples(huge, 0, false); }),
            huge + ":2: material index 10000000000 is too large");
}

TEST_F(Io, CsvHeaderAndEmptyFileErrors) {
  const std::string empty = write("e.csv", "");
  EXPECT_EQ(errorOf([&] { brdfcl::readSamples(empty, 0, false); }),
            empty + ": empty file; expected the header 'material,Lx,Ly,Lz,Vx,Vy,Vz'");
  const std::string blank = write("b.csv", "\n \r\n");
  EXPECT_EQ(errorOf([&] { brdfcl::readSamples(blank, 0, true); }),
            blank + ": empty file; expected the header 'material,Lx,Ly,Lz,Vx,Vy,Vz' or 'Lx,Ly,Lz,Vx,Vy,Vz'");
  const std::string headerOnly = write("h.csv", "material,Lx,Ly,Lz,Vx,Vy,Vz\r\n\r\n");
  EXPECT_EQ(errorOf([&] { brdfcl::readSamples(headerOnly, 0, false); }),
            headerOnly + ": no samples (the file has a header but no rows)");
  const std::string noHeader = write("n.csv", "0,0,0,1,0,0,1\n");
  EXPECT_EQ(errorOf([&] { brdfcl::readSamples(noHeader, 0, false); }),
            noHeader + ":1: missing header; the first line must be 'material,Lx,Ly,Lz,Vx,Vy,Vz'");
  const std::string wrongCase = write("w.csv", "material,lx,ly,lz,vx,vy,vz\n0,0,0,1,0,0,1\n");
  EXPECT_EQ(
      errorOf([&] { brdfcl::readSamples(wrongCase, 0, false); }),
      wrongCase + ": header: unknown column 'lx' (column 2); did you mean Lx? the columns are material,Lx,Ly,Lz,Vx,Vy,Vz "
                  "in any order");
  const std::string missing = path("nope.csv");
  EXPECT_EQ(errorOf([&] { brdfcl::readSamples(missing, 0, false); }),
            "cannot read samples file '" + missing + "': No such file or directory");
}

TEST_F(Io, CsvManyRowsKeepLineNumbers) {
  std::string body = "material,Lx,Ly,Lz,Vx,Vy,Vz\n";
  for (int i = 0; i < 100000; ++i) body += std::to_string(i % 5) + ",0.1,0.2,0.9,-0.3,0.2,0.8\n";
  const std::string good = write("many.csv", body);
  const Samples s = brdfcl::readSamples(good, 5, false);
  ASSERT_EQ(s.size(), 100000u);
  EXPECT_EQ(s.material[99999], 4u);
  body += "1,0,0,0,0,0,1\n";
  const std::string bad = write("bad.csv", body);
  EXPECT_EQ(errorOf([&] { brdfcl::readSamples(bad, 5, false); }), bad + ":100002: L has zero length");
}

// Files of several MiB are split between worker threads (when the machine has several cores):
// order, line numbers and the choice of the first error must not depend on the split.
TEST_F(Io, CsvLargeFileKeepsOrderAndReportsFirstError) {
  const int rows = 200000;
  std::vector<std::string> lines = {"material,Lx,Ly,Lz,Vx,Vy,Vz"};
  for (int i = 0; i < rows; ++i)
    lines.push_back(std::to_string(i % 7) + "," + std::to_string(i) + ",0,1,0," + std::to_string(rows - i) + ",1");
  const auto join = [](const std::vector<std::string>& ls, const std::string& tail) {
    std::string out;
    for (const auto& l : ls) out += l + "\n";
    return out + tail;
  };
  const Samples s = brdfcl::readSamples(write("big.csv", join(lines, std::string(3 << 20, '\n'))), 7, false);
  ASSERT_EQ(s.size(), static_cast<std::size_t>(rows));
  for (int i = 0; i < rows; i += 997) {
    const double lx = i / std::sqrt(double(i) * i + 1.0),
                 vy = (rows - i) / std::sqrt(double(rows - i) * (rows - i) + 1.0);
    ASSERT_EQ(s.material[i], static_cast<std::uint32_t>(i % 7)) << i;
    ASSERT_FLOAT_EQ(s.L[3 * i], static_cast<float>(lx)) << i;
    ASSERT_FLOAT_EQ(s.V[3 * i + 1], static_cast<float>(vy)) << i;
  }

  // Line n of the file is lines[n - 1].
  std::vector<std::string> bad = lines;
  bad[150000] = "0,0,0,0,0,0,1";
  const std::string late = write("late.csv", join(bad, ""));
  EXPECT_EQ(errorOf([&] { brdfcl::readSamples(late, 7, false); }), late + ":150001: L has zero length");
  bad[10] = "0,0,0,1,x,0,1";
  const std::string both = write("both.csv", join(bad, ""));
  EXPECT_EQ(errorOf([&] { brdfcl::readSamples(both, 7, false); }), both + ":11: field 'Vx' is not a number: 'x'");
  bad = lines;
  bad[120000] = "";
  const std::string gap = write("gap.csv", join(bad, "\n\n"));
  EXPECT_EQ(errorOf([&] { brdfcl::readSamples(gap, 7, false); }),
            gap + ":120001: empty line; expected 7 fields (material,Lx,Ly,Lz,Vx,Vy,Vz)");
  bad = lines;
  bad.back() = "9,1,0,0,1,0,0";
  const std::string last = write("last.csv", join(bad, "\r\n"));
  EXPECT_EQ(errorOf([&] { brdfcl::readSamples(last, 7, false); }),
            last + ":" + std::to_string(rows + 1) + ": material index 9 out of range (7 materials)");
}

// ---------------------------------------------------------------------------------------------
// Samples: NPY

// Builds an .npy file by hand, so the tests pin the format rather than our own writer.
std::string npyBytes(const std::string& descr, bool fortran, const std::string& shape, const std::string& data,
                     int major = 1, const std::string& headerOverride = "") {
  std::string header = headerOverride.empty()
                           ? "{'descr': '" + descr + "', 'fortran_order': " + (fortran ? "True" : "False") +
                                 ", 'shape': " + shape + ", }"
                           : headerOverride;
  const std::size_t prefix = major == 1 ? 10 : 12;
  while ((prefix + header.size() + 1) % 64 != 0) header += ' ';
  header += '\n';
  std::string out = std::string("\x93NUMPY", 6) + static_cast<char>(major) + '\0';
  const std::uint32_t len = static_cast<std::uint32_t>(header.size());
  out.append(reinterpret_cast<const char*>(&len), major == 1 ? 2 : 4);
  return out + header + data;
}

template <typename T>
std::string raw(const std::vector<T>& v) {
  return std::string(reinterpret_cast<const char*>(v.data()), v.size() * sizeof(T));
}

const std::vector<double> kRows = {0, 0, 0, 2, 1, 0,  1,  //
                                   2, 3, 4, 0, 0, -5, 0};

void expectTwoRows(const Samples& s, bool withMaterial) {
  ASSERT_EQ(s.size(), 2u);
  if (withMaterial) {
    EXPECT_EQ(s.material, (std::vector<std::uint32_t>{0, 2}));
  }
  const float h = static_cast<float>(1.0 / std::sqrt(2.0));
  const std::vector<float> L = {0, 0, 1, 0.6f, 0.8f, 0}, V = {h, 0, h, 0, -1, 0};
  for (std::size_t i = 0; i < 6; ++i) {
    EXPECT_FLOAT_EQ(s.L[i], L[i]) << i;
    EXPECT_FLOAT_EQ(s.V[i], V[i]) << i;
  }
}

std::vector<double> transpose(const std::vector<double>& rowMajor, std::size_t rows, std::size_t cols) {
  std::vector<double> out(rowMajor.size());
  for (std::size_t i = 0; i < rows; ++i)
    for (std::size_t j = 0; j < cols; ++j) out[j * rows + i] = rowMajor[i * cols + j];
  return out;
}

TEST_F(Io, NpyFloat32AndFloat64AllVersionsAndOrders) {
  const std::vector<float> f32(kRows.begin(), kRows.end());
  const std::vector<double> fortran64 = transpose(kRows, 2, 7);
  const std::vector<float> fortran32(fortran64.begin(), fortran64.end());
  for (int major : {1, 2, 3}) {
    SCOPED_TRACE(major);
    expectTwoRows(brdfcl::readSamples(write("a.npy", npyBytes("<f4", false, "(2, 7)", raw(f32), major)), 3, false),
                  true);
    expectTwoRows(brdfcl::readSamples(write("b.npy", npyBytes("<f8", false, "(2, 7)", raw(kRows), major)), 3, false),
                  true);
    expectTwoRows(brdfcl::readSamples(write("c.npy", npyBytes("<f8", true, "(2, 7)", raw(fortran64), major)), 3, false),
                  true);
    expectTwoRows(brdfcl::readSamples(write("d.npy", npyBytes("<f4", true, "(2, 7)", raw(fortran32), major)), 3, false),
                  true);
  }
  expectTwoRows(brdfcl::readSamples(write("e.npy", npyBytes("|f4", false, "(2, 7)", raw(f32))), 3, false), true);
  expectTwoRows(brdfcl::readSamples(write("f.NPY", npyBytes("=f8", false, "(2, 7)", raw(kRows))), 3, false), true);
  // Python 2 numpy wrote long integers with an L suffix and double-quoted nothing; both forms parse.
  expectTwoRows(brdfcl::readSamples(
                    write("g.npy", npyBytes("", false, "", raw(f32), 1,
                                            "{\"descr\": \"<f4\", \"shape\": (2L, 7L), \"fortran_order\": False}")),
                    3, false),
                true);
}

TEST_F(Io, NpyWithoutMaterialColumn) {
  std::vector<double> six;
  for (std::size_t i = 0; i < kRows.size(); ++i)
    if (i % 7 != 0) six.push_back(kRows[i]);
  const std::string p = write("g.npy", npyBytes("<f8", false, "(2, 6)", raw(six)));
  const Samples s = brdfcl::readSamples(p, 3, true);
  EXPECT_TRUE(s.material.empty());
  expectTwoRows(s, false);
  EXPECT_EQ(errorOf([&] { brdfcl::readSamples(p, 3, false); }),
            p + ": expected shape (N, 7) with columns material,Lx,Ly,Lz,Vx,Vy,Vz, got (2, 6); without the material "
                "column, pass --grid to evaluate every material at each direction pair");
  const std::string f = write("f.npy", npyBytes("<f8", true, "(2, 6)", raw(transpose(six, 2, 6))));
  expectTwoRows(brdfcl::readSamples(f, 3, true), false);
  // A 7-column file in optional mode still has its material indices range-checked.
  const std::string seven = write("s.npy", npyBytes("<f8", false, "(2, 7)", raw(kRows)));
  EXPECT_EQ(errorOf([&] { brdfcl::readSamples(seven, 2, true); }),
            seven + ": row 1: material index 2 out of range (2 materials)");
}

TEST_F(Io, NpyHeaderErrors) {
  const std::vector<float> f32(kRows.begin(), kRows.end());
  struct Case {
    std::string bytes;
    std::string expected;  // message after "<path>: "
  };
  const std::vector<Case> cases = {
      {"material,Lx,Ly,Lz,Vx,Vy,Vz\n", "not an NPY file (no \\x93NUMPY magic); save it with numpy.save"},
      {"", "not an NPY file"},
      {npyBytes(">f4", false, "(2, 7)", raw(f32)),
       "big-endian data ('>f4') is not supported; convert with arr.astype('<f4')"},
      {npyBytes(">f8", false, "(2, 7)", raw(kRows)), "big-endian data ('>f8') is not supported"},
      {npyBytes("<i8", false, "(2, 7)", raw(kRows)),
       "unsupported dtype '<i8'; expected float32 ('<f4') or float64 ('<f8')"},
      {npyBytes("<f2", false, "(2, 7)", raw(kRows)), "unsupported dtype '<f2'"},
      {npyBytes("", false, "", raw(kRows), 1, "{'descr': [('a', '<f8')], 'fortran_order': False, 'shape': (2,), }"),
       "structured dtypes are not supported"},
      {npyBytes("<f8", false, "(14,)", raw(kRows)),
       "expected shape (N, 7) with columns material,Lx,Ly,Lz,Vx,Vy,Vz, got (14,)"},
      {npyBytes("<f8", false, "(2, 7, 1)", raw(kRows)), "got (2, 7, 1)"},
      {npyBytes("<f8", false, "(7, 2)", raw(kRows)), "got (7, 2)"},
      {npyBytes("<f8", false, "(0, 7)", ""), "no samples (shape (0, 7))"},
      {npyBytes("<f4", false, "(1000, 7)", std::string(872 * 28 + 5, '\0')),
       "truncated: expected 1000 rows of 7 float32, file has 872 complete rows"},
      {npyBytes("<f8", false, "(3, 7)", raw(kRows)), "truncated: expected 3 rows of 7 float64, file has 2 complete rows"},
      {npyBytes("<f8", false, "(18446744073709551615, 7)", raw(kRows)),
       "truncated: expected 18446744073709551615 rows of 7 float64, file has 2 complete rows"},
      {npyBytes("", false, "", raw(kRows), 1, "{'descr': '<f8', 'shape': (2, 7)}"),
       "malformed NPY header (needs 'descr', 'fortran_order' and 'shape')"},
      {npyBytes("", false, "", raw(kRows), 1, "{'descr': '<f8', 'fortran_order': maybe, 'shape': (2, 7)}"),
       "malformed NPY header (fortran_order must be True or False)"},
      {npyBytes("", false, "", raw(kRows), 1, "{'descr': '<f8', 'fortran_order': False, 'shape': (2, -7)}"),
       "malformed NPY header (shape must be a tuple of non-negative integers)"},
      {npyBytes("", false, "", raw(kRows), 1, "descr"), "malformed NPY header (expected '{')"},
      {npyBytes("", false, "", raw(kRows), 1, "{'descr: '<f8'}"), "malformed NPY header"},
      {npyBytes("<f8", false, "(2, 7)", raw(kRows), 4),
       "unsupported NPY format version 4.0 (supported: 1.0, 2.0, 3.0)"},
      {std::string("\x93NUMPY\x01\x00\xff\x00{'descr'", 18), "truncated NPY header"},
      {std::string("\x93NUMPY\x02\x00\x05", 9) + std::string(1, '\0'), "truncated NPY header"},
  };
  for (const auto& c : cases) {
    SCOPED_TRACE(c.expected);
    const std::string p = write("bad.npy", c.bytes);
    const std::string m = errorOf([&] { brdfcl::readSamples(p, 3, false); });
    EXPECT_EQ(m.rfind(p + ": ", 0), 0u) << m;
    EXPECT_CONTAINS(m, c.expected);
  }
  // The exact truncation message the docs quote.
  const std::string p = write("s.npy", npyBytes("<f4", false, "(1000, 7)", std::string(872 * 28, '\0')));
  EXPECT_EQ(errorOf([&] { brdfcl::readSamples(p, 3, false); }),
            p + ": truncated: expected 1000 rows of 7 float32, file has 872 complete rows");
}

TEST_F(Io, NpyRowErrorsUseZeroBasedRows) {
  const auto rowError = [&](std::size_t badRow, std::size_t col, double value, std::size_t materialCount = 3) {
    std::vector<double> rows;
    for (std::size_t i = 0; i < 20; ++i) rows.insert(rows.end(), {1, 0, 0, 1, 0, 0, 1});
    rows[badRow * 7 + col] = value;
    const std::string p = write("r.npy", npyBytes("<f8", false, "(20, 7)", raw(rows)));
    const std::string m = errorOf([&] { brdfcl::readSamples(p, materialCount, false); });
    EXPECT_EQ(m.rfind(p + ": row " + std::to_string(badRow) + ": ", 0), 0u) << m;
    return m.substr(std::min(m.size(), p.size()));
  };
  EXPECT_EQ(rowError(12, 0, 12), ": row 12: material index 12 out of range (3 materials)");
  EXPECT_EQ(rowError(0, 0, 3.5), ": row 0: material index 3.5 is not a non-negative integer");
  EXPECT_EQ(rowError(19, 0, -1), ": row 19: material index -1 is not a non-negative integer");
  EXPECT_EQ(rowError(5, 5, std::nan("")), ": row 5: field 'Vy' is not finite: nan");
  EXPECT_EQ(rowError(5, 1, -INFINITY), ": row 5: field 'Lx' is not finite: -inf");
  EXPECT_EQ(rowError(7, 3, 0), ": row 7: L has zero length");
  EXPECT_EQ(rowError(8, 6, 0), ": row 8: V has zero length");
  EXPECT_EQ(rowError(3, 0, 1e12, 0), ": row 3: material index 1000000000000 is too large");

  // Fortran order: the bad value is found at the same (0-based) row.
  std::vector<float> rows;
  for (std::size_t i = 0; i < 4; ++i) rows.insert(rows.end(), {0, 0, 0, 1, 0, 0, 1});
  rows[2 * 7 + 3] = 0;
  std::vector<double> asDouble(rows.begin(), rows.end());
  const std::vector<double> t = transpose(asDouble, 4, 7);
  const std::string p = write("f.npy", npyBytes("<f4", true, "(4, 7)", raw(std::vector<float>(t.begin(), t.end()))));
  EXPECT_EQ(errorOf([&] { brdfcl::readSamples(p, 3, false); }), p + ": row 2: L has zero length");
}

TEST_F(Io, NpyLargeFileKeepsOrderAndReportsFirstError) {
  const std::size_t rows = 300000;
  std::vector<double> data(rows * 7);
  for (std::size_t i = 0; i < rows; ++i) {
    const double row[7] = {double(i % 3), double(i), 0, 1, 1, 0, double(i)};
    std::copy(row, row + 7, data.begin() + static_cast<std::ptrdiff_t>(7 * i));
  }
  const auto check = [&](const Samples& s) {
    ASSERT_EQ(s.size(), rows);
    for (std::size_t i = 0; i < rows; i += 1009) {
      ASSERT_EQ(s.material[i], i % 3) << i;
      ASSERT_FLOAT_EQ(s.L[3 * i], static_cast<float>(i / std::sqrt(double(i) * i + 1.0))) << i;
      ASSERT_FLOAT_EQ(s.V[3 * i + 2], static_cast<float>(i / std::sqrt(double(i) * i + 1.0))) << i;
    }
  };
  const std::vector<float> f32(data.begin(), data.end());
  check(brdfcl::readSamples(write("c.npy", npyBytes("<f4", false, "(300000, 7)", raw(f32))), 3, false));
  const std::vector<double> t = transpose(data, rows, 7);
  check(brdfcl::readSamples(write("f.npy", npyBytes("<f8", true, "(300000, 7)", raw(t))), 3, false));

  data[7 * 250000 + 4] = 0;  // V = (0, 0, 250000): fine
  data[7 * 250000 + 6] = 0;  // V = 0: not
  const std::string late = write("late.npy", npyBytes("<f8", false, "(300000, 7)", raw(data)));
  EXPECT_EQ(errorOf([&] { brdfcl::readSamples(late, 3, false); }), late + ": row 250000: V has zero length");
  data[7 * 20] = 7;
  const std::string both = write("both.npy", npyBytes("<f8", false, "(300000, 7)", raw(data)));
  EXPECT_EQ(errorOf([&] { brdfcl::readSamples(both, 3, false); }),
            both + ": row 20: material index 7 out of range (3 materials)");
}

// ---------------------------------------------------------------------------------------------
// Results and atomic writes

// Minimal reader for what writeResults produces: v1.0, '<f4', C order, shape (N, 3).
std::vector<float> readNpyResults(const std::string& bytes, std::size_t& rows) {
  if (bytes.size() < 10) {
    ADD_FAILURE() << "not an NPY file: " << bytes.size() << " bytes";
    return {};
  }
  EXPECT_EQ(bytes.substr(0, 8), std::string("\x93NUMPY\x01\x00", 8));
  const std::size_t hlen = static_cast<unsigned char>(bytes[8]) | static_cast<unsigned char>(bytes[9]) << 8;
  EXPECT_EQ((10 + hlen) % 64, 0u);
  const std::string header = bytes.substr(10, hlen);
  EXPECT_EQ(header.back(), '\n');
  EXPECT_NE(header.find("'descr': '<f4'"), std::string::npos) << header;
  EXPECT_NE(header.find("'fortran_order': False"), std::string::npos) << header;
  const std::size_t open = header.find("'shape': (");
  EXPECT_NE(open, std::string::npos) << header;
  rows = std::stoull(header.substr(open + 10));
  EXPECT_NE(header.find(", 3)", open), std::string::npos) << header;
  std::vector<float> data((bytes.size() - 10 - hlen) / 4);
  EXPECT_EQ(data.size(), rows * 3);
  if (!data.empty()) std::memcpy(data.data(), bytes.data() + 10 + hlen, data.size() * 4);
  return data;
}

TEST_F(Io, WriteResultsNpyRoundTrip) {
  std::vector<float> rgb;
  for (int i = 0; i < 3000; ++i) rgb.push_back(static_cast<float>(i) * 0.37f - 5.0f);
  rgb[7] = 1e-30f;
  const std::string p = path("out.npy");
  brdfcl::writeResults(p, rgb);
  std::size_t rows = 0;
  const std::vector<float> back = readNpyResults(readFile(p), rows);
  EXPECT_EQ(rows, 1000u);
  EXPECT_EQ(back, rgb);
  EXPECT_EQ(listDir(), (std::vector<std::string>{"out.npy"}));

  // The reader accepts what the writer produces once it has the 7 columns it needs.
  brdfcl::writeResults(path("empty.NPY"), {});
  const std::string empty = readFile(path("empty.NPY"));
  std::size_t emptyRows = 1;
  EXPECT_TRUE(readNpyResults(empty, emptyRows).empty());
  EXPECT_EQ(emptyRows, 0u);
}

TEST_F(Io, WriteResultsCsvUsesNineSignificantDigits) {
  const std::vector<float> rgb = {0.1f, 1.0f, 0.0f, 123456789.0f, 1e-10f, -2.5f, 3.14159265f, 1e30f, 65504.0f};
  const std::string p = path("out.csv");
  brdfcl::writeResults(p, rgb);
  std::string expected = "r,g,b\n";
  char line[128];
  for (std::size_t i = 0; i < rgb.size(); i += 3) {
    std::snprintf(line, sizeof line, "%.9g,%.9g,%.9g\n", rgb[i], rgb[i + 1], rgb[i + 2]);
    expected += line;
  }
  EXPECT_EQ(readFile(p), expected);
  EXPECT_EQ(readFile(p).substr(0, 31), "r,g,b\n0.100000001,1,0\n123456792");
  // Values read back are bit-identical.
  std::istringstream in(readFile(p).substr(6));
  for (float want : rgb) {
    double got = 0;
    char sep;
    in >> got;
    in.get(sep);
    EXPECT_EQ(static_cast<float>(got), want);
  }
}

TEST_F(Io, WriteResultsReplacesExistingFile) {
  const std::string p = write("out.csv", "old content that is longer than the new one\n\n\n\n");
  brdfcl::writeResults(p, {1, 2, 3});
  EXPECT_EQ(readFile(p), "r,g,b\n1,2,3\n");
  EXPECT_EQ(listDir(), (std::vector<std::string>{"out.csv"}));
}

TEST_F(Io, WriteResultsRejectsPartialTriples) {
  EXPECT_THROW(brdfcl::writeResults(path("x.csv"), {1, 2}), std::invalid_argument);
  EXPECT_TRUE(listDir().empty());
}

TEST_F(Io, WriteToMissingDirectoryFailsCleanly) {
  const std::string p = path("out/x.csv");
  EXPECT_EQ(errorOf([&] {
              brdfcl::writeResults(p, {1, 2, 3});
            }),
            "cannot write '" + p + "': No such file or directory");
  EXPECT_TRUE(listDir().empty());
  EXPECT_EQ(errorOf([&] {
              brdfcl::writeResults(dir_.string(), {1, 2, 3});
            }),
            "cannot write '" + dir_.string() + "': it is a directory; name a file inside it");
  fs::create_directory(dir_ / "sub");
  EXPECT_EQ(errorOf([&] {
              brdfcl::writeResults(path("sub"), {1, 2, 3});
            }),
            "cannot write '" + path("sub") + "': it is a directory; name a file inside it");
  EXPECT_EQ(listDir(), (std::vector<std::string>{"sub"}));
}

TEST_F(Io, WriteToReadOnlyDirectoryFailsCleanly) {
  if (::geteuid() == 0) GTEST_SKIP() << "root ignores directory permissions";
  fs::create_directory(dir_ / "ro");
  fs::permissions(dir_ / "ro", fs::perms::owner_read | fs::perms::owner_exec);
  const std::string p = path("ro/x.csv");
  EXPECT_EQ(errorOf([&] { brdfcl::writeResults(p, {1, 2, 3}); }), "cannot write '" + p + "': Permission denied");
  fs::permissions(dir_ / "ro", fs::perms::owner_all);
  EXPECT_TRUE(fs::is_empty(dir_ / "ro"));
}

// Stands in for a full disk: with RLIMIT_FSIZE, write() fails with EFBIG the way it fails with
// ENOSPC, and the writer must notice, report the user's path and leave nothing behind.
TEST_F(Io, WriteFailureMidwayLeavesNoFile) {
  struct rlimit old {};
  ASSERT_EQ(::getrlimit(RLIMIT_FSIZE, &old), 0);
  const auto oldHandler = std::signal(SIGXFSZ, SIG_IGN);
  struct rlimit small = old;
  small.rlim_cur = 4096;
  ASSERT_EQ(::setrlimit(RLIMIT_FSIZE, &small), 0);
  const std::vector<float> rgb(300000, 0.123456789f);
  const std::string csv = path("big.csv"), npy = path("big.npy");
  const std::string m1 = errorOf([&] { brdfcl::writeResults(csv, rgb); });
  const std::string m2 = errorOf([&] { brdfcl::writeResults(npy, rgb); });
  ::setrlimit(RLIMIT_FSIZE, &old);
  std::signal(SIGXFSZ, oldHandler);
  EXPECT_EQ(m1, "cannot write '" + csv + "': File too large");
  EXPECT_EQ(m2, "cannot write '" + npy + "': File too large");
  EXPECT_TRUE(listDir().empty());
}

TEST_F(Io, WriteAtomicallyUsesHiddenTemporaryBeside) {
  const std::string p = path("result.bin");
  std::string seen;
  brdfcl::writeAtomically(p, [&](const std::string& tmp) {
    seen = tmp;
    EXPECT_TRUE(fs::exists(tmp));
    EXPECT_FALSE(fs::exists(p));
    std::ofstream(tmp, std::ios::binary) << "payload";
  });
  EXPECT_EQ(fs::path(seen).parent_path(), dir_);
  EXPECT_EQ(fs::path(seen).filename().string().rfind(".brdfcl.tmp.", 0), 0u) << seen;
  EXPECT_EQ(readFile(p), "payload");
  EXPECT_EQ(listDir(), (std::vector<std::string>{"result.bin"}));
}

TEST_F(Io, WriteAtomicallyRemovesTemporaryOnException) {
  const std::string p = write("keep.csv", "previous\n");
  struct Boom : std::runtime_error {
    Boom() : std::runtime_error("boom") {}
  };
  EXPECT_THROW(brdfcl::writeAtomically(p,
                                       [&](const std::string& tmp) {
                                         std::ofstream(tmp) << "half";
                                         throw Boom();
                                       }),
               Boom);
  EXPECT_EQ(readFile(p), "previous\n");
  EXPECT_EQ(listDir(), (std::vector<std::string>{"keep.csv"}));

  const std::string fresh = path("fresh.csv");
  EXPECT_THROW(brdfcl::writeAtomically(fresh, [](const std::string&) { throw Error("inner"); }), Error);
  EXPECT_EQ(listDir(), (std::vector<std::string>{"keep.csv"}));
}

TEST_F(Io, WriteAtomicallyRelativePathInCurrentDirectory) {
  const fs::path old = fs::current_path();
  fs::current_path(dir_);
  brdfcl::writeResults("rel.csv", {0.5f, 0.25f, 0.125f});
  fs::current_path(old);
  EXPECT_EQ(readFile(path("rel.csv")), "r,g,b\n0.5,0.25,0.125\n");
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
