// Spellings of the EvalOptions enums as the CLI accepts and prints them (material.hpp).
// One table per enum keeps parse, toString and the "use a, b or c" hint from drifting apart.
#include <cstddef>
#include <string>

#include "brdfcl/error.hpp"
#include "brdfcl/material.hpp"
#include "model/profile_version.hpp"
#include "io/option_style.hpp"

namespace brdfcl {
namespace {

template <typename E>
struct Spelling {
  E value;
  const char* name;
};

constexpr Spelling<SheenVisibility> kVisibility[] = {{SheenVisibility::Charlie, "charlie"},
                                                     {SheenVisibility::Ashikhmin, "ashikhmin"}};
constexpr Spelling<SheenDistribution> kDistribution[] = {{SheenDistribution::Charlie, "charlie"},
                                                         {SheenDistribution::Ashikhmin, "ashikhmin"}};
constexpr Spelling<SheenScaling> kScaling[] = {
    {SheenScaling::Min, "min"}, {SheenScaling::View, "view"}, {SheenScaling::None, "none"}};
constexpr Spelling<Lobe> kLobe[] = {{Lobe::All, "all"},
                                    {Lobe::Diffuse, "diffuse"},
                                    {Lobe::Specular, "specular"},
                                    {Lobe::Sheen, "sheen"},
                                    {Lobe::Clearcoat, "clearcoat"}};
constexpr Spelling<Profile> kProfile[] = {{Profile::Spec, "spec"},         {Profile::Khronos, "khronos"},
                                          {Profile::Threejs, "threejs"},   {Profile::Filament, "filament"},
                                          {Profile::Babylon, "babylon"},   {Profile::Materialx, "materialx"}};

// The pins of docs/profiles.md, spelled as there (test_profile_versions checks every hash against it).
struct PinnedEngine {
  Profile profile;
  EngineVersion version;
};
constexpr PinnedEngine kEngines[] = {
    {Profile::Spec,
     {"glTF 2.0", "ratified core, KHR_materials_sheen, KHR_materials_clearcoat and KHR_materials_anisotropy specifications"}},
    {Profile::Khronos,
     {"glTF Sample Renderer",
      "KhronosGroup/glTF-Sample-Renderer pbr.frag@9dfbb82b, material_info.glsl@07d2ba65, "
      "brdf.glsl of glTF-Sample-Viewer@d0b428c8, material.js@aa1ab251 (no release tag)"}},
    {Profile::Threejs,
     {"three.js WebGPU renderer (TSL)",
      "mrdoob/three.js PhysicalLightingModel.js@011d3c8d, BRDF_Sheen.js@011d3c8d, BRDF_GGX.js@3a98b6a0, "
      "F_Schlick.js@15b5d80a, DFGLUT.js@79a613e6, getRoughness.js@07e4c12b (no release tag)"}},
    {Profile::Filament,
     {"Filament",
      "google/filament surface_brdf.fs@04d50d42, surface_shading_model_standard.fs@1b47d187, "
      "common_material.fs@0371a805, desktop (no release tag)"}},
    {Profile::Babylon,
     {"Babylon.js PBRMaterial",
      "BabylonJS/Babylon.js pbrBRDFFunctions.fx@00e0487b, lightFragment.fx@01b83572, pbrBlockSheen.fx@626ee12b, "
      "pbrBlockFinalLitComponents.fx@076e49a1, glTF loader defines (legacy specular energy conservation; no release tag)"}},
    {Profile::Materialx,
     {"MaterialX gltf_pbr",
      "1.39.5+ at commit 4177b2cb (main, 2026-07-01, after release v1.39.5; gltf_pbr nodedef 2.0.1)"}},
};

// The message must stay on one line even if the argument does not.
std::string printable(const std::string& s) {
  std::string out = s;
  for (char& c : out)
    if (static_cast<unsigned char>(c) < 0x20 || c == 0x7f) c = '?';
  return out;
}

template <typename E, std::size_t N>
E parseFrom(const Spelling<E> (&table)[N], const char* option, const std::string& s) {
  for (const auto& entry : table)
    if (s == entry.name) return entry.value;
  // "use a, b or c": the message lists every accepted value so the user needs no manual.
  std::string accepted;
  for (std::size_t i = 0; i < N; ++i) {
    if (i > 0) accepted += (i + 1 == N) ? " or " : ", ";
    accepted += table[i].name;
  }
  throw Error("unknown " + optionName(option) + " value '" + printable(s) + "'; use " + accepted);
}

template <typename E, std::size_t N>
const char* nameOf(const Spelling<E> (&table)[N], E value) {
  for (const auto& entry : table)
    if (entry.value == value) return entry.name;
  return "?";  // only reachable with a value cast from an out-of-range integer
}

}  // namespace

SheenVisibility parseSheenVisibility(const std::string& s) { return parseFrom(kVisibility, "--sheen-visibility", s); }
SheenDistribution parseSheenDistribution(const std::string& s) {
  return parseFrom(kDistribution, "--sheen-distribution", s);
}
SheenScaling parseSheenScaling(const std::string& s) { return parseFrom(kScaling, "--sheen-scaling", s); }
Lobe parseLobe(const std::string& s) { return parseFrom(kLobe, "--lobe", s); }
Profile parseProfile(const std::string& s, const char* option) { return parseFrom(kProfile, option, s); }

const char* toString(SheenVisibility v) { return nameOf(kVisibility, v); }
const char* toString(SheenDistribution d) { return nameOf(kDistribution, d); }
const char* toString(SheenScaling s) { return nameOf(kScaling, s); }
const char* toString(Lobe l) { return nameOf(kLobe, l); }
const char* toString(Profile p) { return nameOf(kProfile, p); }

EngineVersion profileEngineVersion(Profile p) {
  for (const auto& e : kEngines)
    if (e.profile == p) return e.version;
  return {"?", "?"};  // only reachable with a value cast from an out-of-range integer
}

std::string describeProfile(Profile p) {
  const EngineVersion v = profileEngineVersion(p);
  return std::string(toString(p)) + ": " + v.engine + " " + v.version;
}

}  // namespace brdfcl
