// Tests of the input checks: typos in materials files and glTF materials (warnings with
// the JSON path and "did you mean", errors under --strict), a .glb given as materials, CSV samples
// with columns in any order, `--samples -` (CSV or NPY on stdin) and the --grid hint.
#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <random>
#include <sstream>
#include <string>
#include <vector>

#include "brdfcl/error.hpp"
#include "brdfcl/gltf.hpp"
#include "brdfcl/io.hpp"
#include "gltf_builder.hpp"
#include "npy.hpp"
#include "process.hpp"
#include "support.hpp"

namespace fs = std::filesystem;
using brdfcl::MaterialReadOptions;
using brdfcl::Samples;
using brdfcl::test::errorOf;
using brdfcl::test::GltfBuilder;
using brdfcl::test::quadWithMaterial;
using brdfcl::test::RunResult;
using brdfcl::test::ScratchDir;

namespace {

// Typos that once left a factor at its default without a word. `material` is one
// material object; `warning` the whole line the reader must give for it, source name "m.json".
struct Typo {
  const char* material;
  const char* warning;
};
const Typo kTypos[] = {
    {R"({"pbrMetallicRoughness": {"metallicFactor": 0, "roughnessFactor": 0.5},
         "extensions": {"KHR_materials_clearcoat": {"clearcoatFactor": 1, "clearcoatRoughness": 0.5}}})",
     "m.json: materials[0].extensions.KHR_materials_clearcoat.clearcoatRoughness: unknown key, ignored; did you mean "
     "clearcoatRoughnessFactor?"},
    {R"({"extensions": {"KHR_material_sheen": {"sheenColorFactor": [1, 1, 1]}}})",
     "m.json: materials[0].extensions.KHR_material_sheen: unknown extension, ignored; did you mean KHR_materials_sheen?"},
    {R"({"extensions": {"KHR_materials_sheen": {"sheenColourFactor": [1, 1, 1]}}})",
     "m.json: materials[0].extensions.KHR_materials_sheen.sheenColourFactor: unknown key, ignored; did you mean "
     "sheenColorFactor?"},
    {R"({"pbrMetallicRoughness": {"metalicFactor": 0}})",
     "m.json: materials[0].pbrMetallicRoughness.metalicFactor: unknown key, ignored; did you mean metallicFactor?"},
    {R"({"pbrMetalicRoughness": {"metallicFactor": 0}})",
     "m.json: materials[0].pbrMetalicRoughness: unknown key, ignored; did you mean pbrMetallicRoughness?"},
    {R"({"extensions": {"KHR_materials_anisotropy": {"anisotropyStrenght": 0.5}}})",
     "m.json: materials[0].extensions.KHR_materials_anisotropy.anisotropyStrenght: unknown key, ignored; did you "
     "mean anisotropyStrength?"},
};

std::string doc(const std::string& material) { return R"({"asset": {"version": "2.0"}, "materials": [)" + material + "]}"; }

// What --strict makes of a warning, spelt out here rather than by calling the reader's helper.
std::string strictText(std::string warning) {
  const auto at = warning.find(", ignored");
  if (at != std::string::npos) warning.erase(at, std::strlen(", ignored"));
  return warning + " (an error under --strict)";
}

std::vector<std::string> warningsOf(const std::string& text, bool strict = false) {
  std::vector<std::string> out;
  MaterialReadOptions o;
  o.warn = [&](const std::string& w) { out.push_back(w); };
  o.strict = strict;
  brdfcl::parseMaterials(text, "m.json", o);
  return out;
}

void writeFile(const std::string& path, const std::string& bytes) {
  std::ofstream(path, std::ios::binary).write(bytes.data(), std::streamsize(bytes.size()));
}

// Rows material, L, V with directions exact in float (multiples of 1/8).
std::vector<double> rows(std::size_t n, unsigned materials) {
  std::mt19937 rng(14);
  std::uniform_int_distribution<int> d(-8, 8), up(1, 8);
  std::vector<double> v;
  for (std::size_t i = 0; i < n; ++i) {
    v.push_back(double(i % materials));
    for (int k = 0; k < 2; ++k) {
      v.push_back(d(rng) / 8.0);
      v.push_back(d(rng) / 8.0);
      v.push_back(up(rng) / 8.0);
    }
  }
  return v;
}

// The rows as CSV with the columns in `order` (indices into material,Lx,..,Vz).
std::string csv(const std::vector<double>& v, const std::vector<int>& order) {
  static const char* names[7] = {"material", "Lx", "Ly", "Lz", "Vx", "Vy", "Vz"};
  std::ostringstream s;
  for (std::size_t k = 0; k < order.size(); ++k) s << (k ? "," : "") << names[order[k]];
  s << "\n";
  for (std::size_t r = 0; r < v.size() / 7; ++r) {
    for (std::size_t k = 0; k < order.size(); ++k) s << (k ? "," : "") << v[7 * r + std::size_t(order[k])];
    s << "\n";
  }
  return s.str();
}

void expectSameSamples(const Samples& a, const Samples& b) {
  EXPECT_EQ(a.material, b.material);
  EXPECT_EQ(a.L, b.L);
  EXPECT_EQ(a.V, b.V);
}

class InputChecksCli : public ::testing::Test {
 protected:
  ScratchDir dir_{"input-checks"};
  std::string write(const std::string& name, const std::string& bytes) const {
    writeFile(dir_.path(name), bytes);
    return dir_.path(name);
  }
  RunResult run(const std::vector<std::string>& args) const {
    std::vector<std::string> argv{BRDFCL_CLI_PATH};
    argv.insert(argv.end(), args.begin(), args.end());
    return brdfcl::test::runProcess(argv, dir_.dir());
  }
  // A shell line, for stdin from a pipe or a redirect; paths here hold no quotes.
  RunResult shell(const std::string& line) const { return brdfcl::test::runProcess({"/bin/sh", "-c", line}, dir_.dir()); }
  RunResult eval(const std::string& materials, const std::string& samples, const std::string& out,
                 std::vector<std::string> extra = {}) const {
    std::vector<std::string> args{"eval", "--materials", materials, "--samples", samples, "--out", out};
    args.insert(args.end(), extra.begin(), extra.end());
    return run(args);
  }
  static void expectUserError(const RunResult& r, const std::string& line) {
    EXPECT_EQ(r.status, 2) << r.describe();
    const auto lines = r.errorLines();
    ASSERT_EQ(lines.size(), 1u) << r.describe();
    EXPECT_EQ(lines[0], "brdfcl: " + line);
  }
  std::string samples() const { return write("s.csv", "material,Lx,Ly,Lz,Vx,Vy,Vz\n0,0,0,1,0,0,1\n0,0.6,0,0.8,-0.6,0,0.8\n"); }
};

}  // namespace

// ---------------------------------------------------------------------------------------------
// Materials files: the library

TEST(MaterialsKeys, EachTypoWarnsWithPathAndSuggestion) {
  for (const Typo& t : kTypos) {
    SCOPED_TRACE(t.material);
    EXPECT_EQ(warningsOf(doc(t.material)), std::vector<std::string>{t.warning});
    // Strict: the finding is the error, and nothing is returned.
    EXPECT_EQ(errorOf([&] { warningsOf(doc(t.material), true); }), strictText(t.warning));
  }
}

// What the typo cost: the clearcoat stayed a mirror coat (roughness 0), as the issue measured.
TEST(MaterialsKeys, ClearcoatRoughnessTypoLeavesTheDefaultAndSaysSo) {
  std::vector<std::string> warnings;
  MaterialReadOptions o;
  o.warn = [&](const std::string& w) { warnings.push_back(w); };
  const auto m = brdfcl::parseMaterials(doc(kTypos[0].material), "m.json", o);
  ASSERT_EQ(m.size(), 1u);
  EXPECT_EQ(m[0].clearcoat, 1.0f);
  EXPECT_EQ(m[0].clearcoatRoughness, 0.0f);
  ASSERT_EQ(warnings.size(), 1u);
  EXPECT_NE(warnings[0].find("did you mean clearcoatRoughnessFactor?"), std::string::npos);
}

TEST(MaterialsKeys, ExtrasVendorAndRealNonMaterialExtensionsAreSilent) {
  const std::string m = R"({
    "name": "x", "extras": {"anything": 1}, "alphaMode": "MASK", "alphaCutoff": 0.3, "doubleSided": true,
    "emissiveFactor": [0, 0, 0],
    "pbrMetallicRoughness": {"metallicFactor": 0, "extras": {}, "extensions": {"ACME_pbr_magic": {}},
      "baseColorTexture": {"index": 0, "texCoord": 0, "extras": {},
        "extensions": {"KHR_texture_transform": {"offset": [0, 0]}, "MSFT_texture_dds": {}}}},
    "occlusionTexture": {"index": 1, "strength": 0.5}, "normalTexture": {"index": 2, "scale": 1},
    "extensions": {
      "ADOBE_materials_thin_transparency": {"whatever": 1},
      "KHR_materials_sheen": {"sheenColorFactor": [1, 0, 0], "sheenRoughnessFactor": 0.5, "extras": {}},
      "KHR_materials_clearcoat": {"clearcoatFactor": 0.5, "extensions": {"VENDOR_x": {}}},
      "KHR_materials_anisotropy": {"anisotropyStrength": 0.5, "anisotropyRotation": 1}}})";
  const auto w = warningsOf(doc(m));
  ASSERT_EQ(w.size(), 1u) << ::testing::PrintToString(w);
  EXPECT_NE(w[0].find("texture references are ignored"), std::string::npos) << w[0];
  EXPECT_NO_THROW(warningsOf(doc(m), true));  // texture notes stay notes under strict
  // The draft's keys are known to the materials reader.
  EXPECT_TRUE(warningsOf(doc(R"({"extensions": {"KHR_materials_sheen": {"intensityFactor": 0.5, "colorFactor": [1, 1, 1]}}})")).empty());
}

TEST(MaterialsKeys, LeftOutExtensionsWarnOnceNamingWhatIsIgnored) {
  const char* names[] = {"KHR_materials_specular",        "KHR_materials_transmission",
                         "KHR_materials_volume",       "KHR_materials_iridescence",     "KHR_materials_emissive_strength",
                         "KHR_materials_dispersion",   "KHR_materials_diffuse_transmission", "KHR_materials_unlit",
                         "KHR_materials_pbrSpecularGlossiness", "KHR_materials_variants"};
  std::string ext;
  for (const char* n : names) ext += std::string(ext.empty() ? "" : ", ") + "\"" + n + "\": {}";
  const auto w = warningsOf(doc(R"({"extensions": {)" + ext + "}}"));
  ASSERT_EQ(w.size(), std::size(names));
  for (const std::string& line : w) {
    EXPECT_EQ(line.rfind("m.json: materials[0].extensions.KHR_materials_", 0), 0u) << line;
    EXPECT_NE(line.find(": ignored: "), std::string::npos) << line;
  }
  EXPECT_EQ(warningsOf(doc(R"({"extensions": {"KHR_materials_specular": {"specularFactor": 0.5}}})")),
            std::vector<std::string>{"m.json: materials[0].extensions.KHR_materials_specular: ignored: brdfcl's f has "
                                     "no specular strength or color input (dielectric F0 stays 0.04, F90 stays 1)"});
  // KHR_materials_ior is read (the engine profiles use it): silent, its keys checked.
  EXPECT_TRUE(warningsOf(doc(R"({"extensions": {"KHR_materials_ior": {"ior": 1.8}}})")).empty());
  EXPECT_EQ(warningsOf(doc(R"({"extensions": {"KHR_materials_ior": {"iorr": 1.8}}})")).size(), 1u);
  EXPECT_EQ(errorOf([&] { warningsOf(doc(R"({"extensions": {"KHR_materials_transmission": {}}})"), true); }),
            "m.json: materials[0].extensions.KHR_materials_transmission: not evaluated: brdfcl's f is a reflection "
            "BRDF; transmitted light is not modelled (an error under --strict)");
}

TEST(MaterialsKeys, FarTyposListWhatIsKnownAndTextureInfosAreChecked) {
  EXPECT_EQ(warningsOf(doc(R"({"extensions": {"KHR_materials_fluorescence": {}}})")),
            std::vector<std::string>{"m.json: materials[0].extensions.KHR_materials_fluorescence: unknown extension, "
                                     "ignored (brdfcl reads KHR_materials_sheen, KHR_materials_clearcoat, "
                                     "KHR_materials_anisotropy, KHR_materials_ior)"});
  // Lower-case prefixes are Khronos typos too, not a vendor's.
  EXPECT_EQ(warningsOf(doc(R"({"extensions": {"khr_materials_clearcoat": {}}})")),
            std::vector<std::string>{"m.json: materials[0].extensions.khr_materials_clearcoat: unknown extension, "
                                     "ignored; did you mean KHR_materials_clearcoat?"});
  auto w = warningsOf(doc(R"({"pbrMetallicRoughness": {"baseColorTexture": {"indx": 0,
                               "extensions": {"KHR_texture_transfrom": {}}}}})"));
  ASSERT_EQ(w.size(), 3u) << ::testing::PrintToString(w);  // two findings, then the texture note
  EXPECT_EQ(w[0], "m.json: materials[0].pbrMetallicRoughness.baseColorTexture.extensions.KHR_texture_transfrom: "
                  "unknown extension, ignored; did you mean KHR_texture_transform?");
  EXPECT_EQ(w[1], "m.json: materials[0].pbrMetallicRoughness.baseColorTexture.indx: unknown key, ignored; did you "
                  "mean index?");
  EXPECT_NE(w[2].find("texture references are ignored"), std::string::npos) << w[2];
  w = warningsOf(doc(R"({"roughness": 0.5, "foo": 1})"));
  ASSERT_EQ(w.size(), 2u) << ::testing::PrintToString(w);
  EXPECT_EQ(w[0], "m.json: materials[0].foo: unknown key, ignored (known here: name, pbrMetallicRoughness, "
                  "normalTexture, occlusionTexture, emissiveTexture, emissiveFactor, alphaMode, alphaCutoff, "
                  "doubleSided, extensions, extras)");
  // A type error is still the reader's, before any key is looked at.
  EXPECT_EQ(errorOf([&] { warningsOf(doc(R"({"pbrMetalicRoughness": 1, "pbrMetallicRoughness": 2})"), true); }),
            "m.json: materials[0].pbrMetallicRoughness: expected an object, got 2");
}

TEST(MaterialsKeys, ExistingSignaturesStayNonStrict) {
  std::vector<std::string> w;
  const auto m = brdfcl::parseMaterials(doc(kTypos[3].material), "m.json", [&](const std::string& s) { w.push_back(s); });
  EXPECT_EQ(m.size(), 1u);
  EXPECT_EQ(w, std::vector<std::string>{kTypos[3].warning});
  EXPECT_NO_THROW(brdfcl::parseMaterials(doc(kTypos[3].material), "m.json"));
}

TEST(MaterialsKeys, GlbIsReadThroughItsJsonChunk) {
  ScratchDir dir("input-checks-glb");
  const std::string text = doc(R"({"name": "a", "pbrMetallicRoughness": {"metallicFactor": 0.25, "roughnessFactor": 0.5}},
                                  {"extensions": {"KHR_materials_clearcoat": {"clearcoatFactor": 0.5}}})");
  const std::string glb = GltfBuilder::glb(text, std::string(8, '\0'));
  writeFile(dir.path("m.glb"), glb);
  writeFile(dir.path("m.gltf"), text);
  const auto fromGlb = brdfcl::readMaterials(dir.path("m.glb"));
  const auto fromGltf = brdfcl::readMaterials(dir.path("m.gltf"));
  ASSERT_EQ(fromGlb.size(), 2u);
  EXPECT_EQ(fromGlb[0].name, "a");
  EXPECT_EQ(fromGlb[0].metallic, 0.25f);
  EXPECT_EQ(fromGlb[1].clearcoat, fromGltf[1].clearcoat);
  // Typos are found in a .glb's JSON as in a .gltf, named by the .glb.
  writeFile(dir.path("t.glb"), GltfBuilder::glb(doc(kTypos[3].material), ""));
  MaterialReadOptions strict;
  strict.strict = true;
  EXPECT_EQ(errorOf([&] { brdfcl::readMaterials(dir.path("t.glb"), strict); }),
            dir.path("t.glb") + ": materials[0].pbrMetallicRoughness.metalicFactor: unknown key; did you mean "
                                "metallicFactor? (an error under --strict)");

  writeFile(dir.path("cut.glb"), glb.substr(0, glb.size() - 10));
  EXPECT_EQ(errorOf([&] { brdfcl::readMaterials(dir.path("cut.glb")); }),
            dir.path("cut.glb") + ": truncated GLB file: the header says " + std::to_string(glb.size()) +
                " bytes, the file has " + std::to_string(glb.size() - 10) + "; download or export it again");
  std::string v1 = glb;
  v1[4] = 1;
  writeFile(dir.path("v1.glb"), v1);
  EXPECT_EQ(errorOf([&] { brdfcl::readMaterials(dir.path("v1.glb")); }),
            dir.path("v1.glb") + ": unsupported GLB version 1; brdfcl reads glTF 2.0 binaries (version 2)");
  std::string notJson = glb;
  std::memcpy(&notJson[16], "BIN\0", 4);
  writeFile(dir.path("nj.glb"), notJson);
  EXPECT_EQ(errorOf([&] { brdfcl::readMaterials(dir.path("nj.glb")); }),
            dir.path("nj.glb") + ": GLB chunk 0 is not JSON; re-export the file");
  writeFile(dir.path("text.glb"), text);
  EXPECT_EQ(errorOf([&] { brdfcl::readMaterials(dir.path("text.glb")); }),
            dir.path("text.glb") + ": not a GLB file (no glTF magic number); a .glb must start with 'glTF'");
}

// ---------------------------------------------------------------------------------------------
// glTF assets: the same checks, through Asset::warnings and LoadOptions::strict

namespace {
std::vector<std::string> keyWarnings(const brdfcl::gltf::Asset& a) {
  std::vector<std::string> out;
  for (const auto& w : a.warnings)
    if (w.find("materials[") != std::string::npos) out.push_back(w);
  return out;
}
}  // namespace

TEST(GltfKeys, TyposWarnInAssetWarningsAndStrictFails) {
  ScratchDir dir("input-checks-gltf");
  for (const Typo& t : kTypos) {
    SCOPED_TRACE(t.material);
    const std::string p = quadWithMaterial(nlohmann::json::parse(t.material)).write(dir.dir(), "a.gltf");
    const std::string expected = p + std::string(t.warning).substr(std::strlen("m.json"));
    EXPECT_EQ(keyWarnings(brdfcl::gltf::load(p)), std::vector<std::string>{expected});
    brdfcl::gltf::LoadOptions strict;
    strict.strict = true;
    EXPECT_EQ(errorOf([&] { brdfcl::gltf::load(p, strict); }), strictText(expected));
  }
}

TEST(GltfKeys, TheLoaderKnowsItsOwnExtensionsAndLeavesOutOnlyThroughExtensionsUsed) {
  ScratchDir dir("input-checks-gltf2");
  // emissive_strength is read by the loader, so its typo is a key typo; the draft sheen is not.
  GltfBuilder b = quadWithMaterial(nlohmann::json::parse(R"({
    "extras": {"x": 1},
    "extensions": {"KHR_materials_emissive_strength": {"emissiveStrenght": 4},
                   "KHR_materials_sheen": {"intensityFactor": 1},
                   "KHR_materials_ior": {"ior": 1.4}, "ACME_velvet": {}}})"));
  b.useExtension("KHR_materials_ior");
  const std::string p = b.write(dir.dir(), "a.gltf");
  const auto a = brdfcl::gltf::load(p);
  const auto w = keyWarnings(a);
  ASSERT_EQ(w.size(), 2u) << ::testing::PrintToString(a.warnings);
  EXPECT_EQ(w[0], p + ": materials[0].extensions.KHR_materials_emissive_strength.emissiveStrenght: unknown key, "
                      "ignored; did you mean emissiveStrength?");
  EXPECT_EQ(w[1].rfind(p + ": materials[0].extensions.KHR_materials_sheen.intensityFactor: unknown key, ignored", 0), 0u)
      << w[1];
  // KHR_materials_ior: one warning for the file, from extensionsUsed, none per material.
  std::size_t ior = 0;
  for (const auto& line : a.warnings) ior += line.find("KHR_materials_ior") != std::string::npos;
  EXPECT_EQ(ior, 1u) << ::testing::PrintToString(a.warnings);
}

// ---------------------------------------------------------------------------------------------
// Samples: columns by name, the header's messages, the --grid hint

TEST(IoSamplesInput, ColumnsInAnyOrderReadLikeTheCanonicalOrder) {
  ScratchDir dir("input-checks-columns");
  // Enough rows for several parse threads and several stream chunks.
  const auto v = rows(300000, 5);
  writeFile(dir.path("c.csv"), csv(v, {0, 1, 2, 3, 4, 5, 6}));
  writeFile(dir.path("r.csv"), csv(v, {6, 3, 0, 4, 1, 5, 2}));
  const Samples canonical = brdfcl::readSamples(dir.path("c.csv"), 5, false);
  expectSameSamples(brdfcl::readSamples(dir.path("r.csv"), 5, false), canonical);
  // Chunked, as eval streams it.
  brdfcl::SampleStream stream(dir.path("r.csv"), 5, false);
  Samples chunk, all;
  while (stream.next(70001, chunk)) {
    all.material.insert(all.material.end(), chunk.material.begin(), chunk.material.end());
    all.L.insert(all.L.end(), chunk.L.begin(), chunk.L.end());
    all.V.insert(all.V.end(), chunk.V.begin(), chunk.V.end());
  }
  expectSameSamples(all, canonical);

  // Without the material column (grid mode), and quoted names.
  writeFile(dir.path("g.csv"), "\"Vz\",Lx,Ly,Lz,Vx,Vy\n1,0.6,0,0.8,0,0\n");
  const Samples g = brdfcl::readSamples(dir.path("g.csv"), 0, true);
  EXPECT_TRUE(g.material.empty());
  EXPECT_EQ(g.L, (std::vector<float>{0.6f, 0.0f, 0.8f}));
  EXPECT_EQ(g.V, (std::vector<float>{0.0f, 0.0f, 1.0f}));
  // Messages name the file's own columns.
  writeFile(dir.path("bad.csv"), "Vz,material,Lx,Ly,Lz,Vx,Vy\n1,0,0,0,1,0,x\n");
  EXPECT_EQ(errorOf([&] { brdfcl::readSamples(dir.path("bad.csv"), 1, false); }),
            dir.path("bad.csv") + ":2: field 'Vy' is not a number: 'x'");
  writeFile(dir.path("short.csv"), "Vz,material,Lx,Ly,Lz,Vx,Vy\n1,0,0,0,1,0\n");
  EXPECT_EQ(errorOf([&] { brdfcl::readSamples(dir.path("short.csv"), 1, false); }),
            dir.path("short.csv") + ":2: expected 7 fields (Vz,material,Lx,Ly,Lz,Vx,Vy), got 6");
}

TEST(IoSamplesInput, HeaderNamesTheMissingUnknownOrRepeatedColumn) {
  ScratchDir dir("input-checks-header");
  const auto err = [&](const std::string& name, const std::string& text, bool optional = false) {
    writeFile(dir.path(name), text);
    return errorOf([&] { brdfcl::readSamples(dir.path(name), 0, optional); });
  };
  EXPECT_EQ(err("s.csv", "material,Lx,Ly,Lz,Vx,Vy\n0,0,0,1,0,0\n"), dir.path("s.csv") + ": header: missing column Vz");
  EXPECT_EQ(err("t.csv", "material,Lx,Vy,Vx\n0,0,0,1\n"), dir.path("t.csv") + ": header: missing columns Ly, Lz, Vz");
  EXPECT_EQ(err("u.csv", "material,Lx,Ly,Lz,Vx,Vy,Vw\n0,0,0,1,0,0,1\n"),
            dir.path("u.csv") + ": header: unknown column 'Vw' (column 7); did you mean Vx? the columns are "
                                "material,Lx,Ly,Lz,Vx,Vy,Vz in any order");
  EXPECT_EQ(err("w.csv", "material,Lx,Ly,Lz,Vx,Vy,Vz,weight\n0,0,0,1,0,0,1,1\n"),
            dir.path("w.csv") + ": header: unknown column 'weight' (column 8); the columns are "
                                "material,Lx,Ly,Lz,Vx,Vy,Vz in any order");
  EXPECT_EQ(err("d.csv", "material,Lx,Ly,Lz,Vx,Vy,Vz,Lx\n0,0,0,1,0,0,1,0\n"),
            dir.path("d.csv") + ": header: column 'Lx' appears twice (columns 2 and 8)");
}

TEST(IoSamplesInput, NoMaterialColumnWithoutGridSuggestsGrid) {
  ScratchDir dir("input-checks-grid");
  writeFile(dir.path("g.csv"), "Lx,Ly,Lz,Vx,Vy,Vz\n0,0,1,0,0,1\n");
  EXPECT_EQ(errorOf([&] { brdfcl::readSamples(dir.path("g.csv"), 2, false); }),
            dir.path("g.csv") +
                ": header: missing column material; add it, or pass --grid to evaluate every material at each direction pair");
  std::vector<double> six = {0, 0, 1, 0, 0, 1};
  writeFile(dir.path("g.npy"), brdfcl::test::npyArray(six, 6, false));
  EXPECT_EQ(errorOf([&] { brdfcl::readSamples(dir.path("g.npy"), 2, false); }),
            dir.path("g.npy") + ": expected shape (N, 7) with columns material,Lx,Ly,Lz,Vx,Vy,Vz, got (1, 6); without "
                                "the material column, pass --grid to evaluate every material at each direction pair");
}

// ---------------------------------------------------------------------------------------------
// The CLI

TEST_F(InputChecksCli, EvalWarnsOnEachTypoAndStrictMakesItTheError) {
  const std::string s = samples();
  for (const Typo& t : kTypos) {
    SCOPED_TRACE(t.material);
    const std::string m = write("m.json", doc(t.material));
    const std::string expected = m + std::string(t.warning).substr(std::strlen("m.json"));
    const RunResult r = eval(m, s, dir_.path("o.csv"));
    ASSERT_EQ(r.status, 0) << r.describe();
    EXPECT_EQ(r.warningLines(), std::vector<std::string>{"brdfcl: warning: " + expected});
    EXPECT_TRUE(fs::exists(dir_.path("o.csv")));
    fs::remove(dir_.path("o.csv"));

    const RunResult strict = eval(m, s, dir_.path("o.csv"), {"--strict"});
    expectUserError(strict, strictText(expected));
    EXPECT_TRUE(strict.warningLines().empty()) << strict.describe();
    EXPECT_FALSE(fs::exists(dir_.path("o.csv")));
  }
  // Under --strict the error comes before the texture note: nothing but the error is printed.
  const std::string textured =
      write("t.json", doc(R"({"pbrMetallicRoughness": {"metalicFactor": 0, "baseColorTexture": {"index": 0}}})"));
  const RunResult tr = eval(textured, s, dir_.path("o.csv"), {"--strict"});
  expectUserError(tr, textured + ": materials[0].pbrMetallicRoughness.metalicFactor: unknown key; did you mean "
                                 "metallicFactor? (an error under --strict)");
  EXPECT_TRUE(tr.warningLines().empty()) << tr.describe();
  // extras and vendor extensions: silent even under --strict.
  const std::string quiet =
      write("q.json", doc(R"({"extras": {"a": 1}, "extensions": {"ACME_x": {}, "KHR_materials_clearcoat": {"extras": {}}}})"));
  const RunResult r = eval(quiet, s, dir_.path("o.csv"), {"--strict"});
  EXPECT_EQ(r.status, 0) << r.describe();
  EXPECT_TRUE(r.err.empty()) << r.err;
  // A left-out extension: one warning naming what is ignored.
  const std::string spec = write("i.json", doc(R"({"extensions": {"KHR_materials_specular": {"specularFactor": 2}}})"));
  const RunResult w = eval(spec, s, dir_.path("i.csv"));
  ASSERT_EQ(w.status, 0) << w.describe();
  EXPECT_EQ(w.warningLines(), std::vector<std::string>{"brdfcl: warning: " + spec +
                                                      ": materials[0].extensions.KHR_materials_specular: ignored: brdfcl's "
                                                      "f has no specular strength or color input (dielectric F0 stays 0.04, "
                                                      "F90 stays 1)"});
}

TEST_F(InputChecksCli, GlbMaterialsEvaluateLikeTheirJson) {
  const std::string text = doc(R"({"pbrMetallicRoughness": {"metallicFactor": 0, "roughnessFactor": 0.4},
                                    "extensions": {"KHR_materials_sheen": {"sheenColorFactor": [1, 0.5, 0.2]}}})");
  const std::string s = samples();
  ASSERT_EQ(eval(write("m.gltf", text), s, dir_.path("a.csv")).status, 0);
  const std::string glb = GltfBuilder::glb(text, "");
  const RunResult r = eval(write("m.glb", glb), s, dir_.path("b.csv"));
  ASSERT_EQ(r.status, 0) << r.describe();
  EXPECT_EQ(brdfcl::test::slurp(dir_.path("a.csv")), brdfcl::test::slurp(dir_.path("b.csv")));
  const std::string cut = write("cut.glb", glb.substr(0, 30));
  expectUserError(eval(cut, s, dir_.path("c.csv")), cut + ": truncated GLB file: the header says " +
                                                       std::to_string(glb.size()) +
                                                       " bytes, the file has 30; download or export it again");
  EXPECT_FALSE(fs::exists(dir_.path("c.csv")));
}

TEST_F(InputChecksCli, SamplesFromStdinAsCsvOrNpy) {
  const std::string m = write("m.json", doc(R"({"pbrMetallicRoughness": {"metallicFactor": 0, "roughnessFactor": 0.5}},
                                               {"extensions": {"KHR_materials_clearcoat": {"clearcoatFactor": 1}}})"));
  const auto v = rows(1000, 2);
  const std::string c = write("s.csv", csv(v, {0, 1, 2, 3, 4, 5, 6}));
  const std::string n = write("s.npy", brdfcl::test::npyArray(v, 7, false));
  ASSERT_EQ(eval(m, c, dir_.path("ref.csv")).status, 0);
  const std::string ref = brdfcl::test::slurp(dir_.path("ref.csv"));
  const std::string cli = BRDFCL_CLI_PATH;
  const std::string args = " eval --materials " + m + " --samples - --out ";
  struct Case {
    const char* what;
    std::string line, out;
  };
  const Case cases[] = {
      {"CSV through a pipe", "cat " + c + " | " + cli + args + dir_.path("p.csv"), dir_.path("p.csv")},
      {"NPY through a pipe", "cat " + n + " | " + cli + args + dir_.path("q.csv"), dir_.path("q.csv")},
      {"CSV redirected from a file", cli + args + dir_.path("r.csv") + " < " + c, dir_.path("r.csv")},
      {"NPY redirected from a file, in small chunks", cli + args + dir_.path("t.csv") + " --chunk 7 < " + n,
       dir_.path("t.csv")},
  };
  for (const Case& k : cases) {
    SCOPED_TRACE(k.what);
    const RunResult r = shell(k.line);
    ASSERT_EQ(r.status, 0) << r.describe();
    EXPECT_EQ(brdfcl::test::slurp(k.out), ref);
  }
  // Messages call it <stdin>.
  const RunResult bad = shell("printf 'material,Lx,Ly,Lz,Vx,Vy,Vz\\n0,0,0,1,0,0,x\\n' | " + cli + args + dir_.path("x.csv"));
  expectUserError(bad, "<stdin>:2: field 'Vz' is not a number: 'x'");
  EXPECT_FALSE(fs::exists(dir_.path("x.csv")));
}

TEST_F(InputChecksCli, MissingMaterialColumnSuggestsGridAndReorderedColumnsMatch) {
  const std::string m = write("m.json", doc("{}"));
  const std::string g = write("g.csv", "Lx,Ly,Lz,Vx,Vy,Vz\n0,0,1,0,0,1\n");
  expectUserError(eval(m, g, dir_.path("o.csv")),
                  g + ": header: missing column material; add it, or pass --grid to evaluate every material at each "
                      "direction pair");
  EXPECT_FALSE(fs::exists(dir_.path("o.csv")));
  EXPECT_EQ(eval(m, g, dir_.path("o.csv"), {"--grid"}).status, 0);

  const auto v = rows(50, 1);
  ASSERT_EQ(eval(m, write("c.csv", csv(v, {0, 1, 2, 3, 4, 5, 6})), dir_.path("c.out.csv")).status, 0);
  ASSERT_EQ(eval(m, write("r.csv", csv(v, {4, 5, 6, 1, 2, 3, 0})), dir_.path("r.out.csv")).status, 0);
  EXPECT_EQ(brdfcl::test::slurp(dir_.path("c.out.csv")), brdfcl::test::slurp(dir_.path("r.out.csv")));
}

TEST_F(InputChecksCli, GltfRenderWarnsAndStrictFails) {
  const std::string p = quadWithMaterial(nlohmann::json::parse(kTypos[3].material)).write(dir_.dir(), "a.gltf");
  const std::string expected = p + std::string(kTypos[3].warning).substr(std::strlen("m.json"));
  const RunResult r = run({"gbuffer", "--gltf", p, "--size", "8x8", "--out", dir_.path("g.exr")});
  ASSERT_EQ(r.status, 0) << r.describe();
  const auto w = r.warningLines();
  EXPECT_NE(std::find(w.begin(), w.end(), "brdfcl: warning: " + expected), w.end()) << r.describe();
  fs::remove(dir_.path("g.exr"));
  expectUserError(run({"gbuffer", "--gltf", p, "--size", "8x8", "--out", dir_.path("g.exr"), "--strict"}),
                  strictText(expected));
  EXPECT_FALSE(fs::exists(dir_.path("g.exr")));
  expectUserError(run({"gbuffer", "--strict", "--out", dir_.path("g.exr")}), "--strict applies to glTF assets; add --gltf FILE");
}
