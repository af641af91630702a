// glTF material parameters as the specs define them, and the options that choose between the
// sheen variants. This is the vocabulary shared by the host library, the CLI and the tests.
#pragma once
#include <array>
#include <cstdint>
#include <string>

namespace brdfcl {

using Rgb = std::array<float, 3>;

// The draft's intensityFactor has no maximum in 001, but the sheen lobe reaches intensity x 2e5
// (Charlie D at the alpha clamp times Ashikhmin V at the cosine floor): far above 1e30 f overflows
// float, and inf x 0 in the clearcoat layering then gives NaN. Larger values are rejected.
constexpr float kMaxDraftIntensity = 1e30f;

// One glTF 2.0 material: pbrMetallicRoughness + KHR_materials_sheen (ratified or draft keys)
// + KHR_materials_clearcoat + KHR_materials_anisotropy. Defaults are the specs' defaults.
struct MaterialParams {
  std::string name;
  Rgb baseColor{1.0f, 1.0f, 1.0f};
  float metallic = 1.0f;
  float roughness = 1.0f;

  // Ratified KHR_materials_sheen (the KHR_materials_sheen specification).
  Rgb sheenColor{0.0f, 0.0f, 0.0f};
  float sheenRoughness = 0.0f;

  // Experimental draft (the experimental KHR_materials_sheen draft): used when the extension object has the
  // draft keys intensityFactor/colorFactor. Sheen roughness is then the material roughness.
  // draftIntensity lies in [0, kMaxDraftIntensity].
  bool draftSheen = false;
  float draftIntensity = 1.0f;
  Rgb draftColor{1.0f, 1.0f, 1.0f};

  // KHR_materials_clearcoat (the KHR_materials_clearcoat specification).
  float clearcoat = 0.0f;
  float clearcoatRoughness = 0.0f;

  // KHR_materials_anisotropy (the KHR_materials_anisotropy specification).
  float anisotropyStrength = 0.0f;
  float anisotropyRotation = 0.0f;  // radians, counter-clockwise from T in the tangent plane
  // Whether the material names KHR_materials_anisotropy at all: the khronos profile takes its
  // anisotropic path on presence, strength 0 included (docs/profiles.md "khronos").
  bool anisotropyExtension = false;

  // KHR_materials_ior. The spec profile's f has no IOR input (F0 stays 0.04); the engine profiles
  // read it as their engines do (docs/profiles.md).
  float ior = 1.5f;

  // Emission is not part of f; kept for the G-buffer path.
  Rgb emissive{0.0f, 0.0f, 0.0f};
};

enum class SheenVisibility { Charlie, Ashikhmin };
enum class SheenDistribution { Charlie, Ashikhmin };
enum class SheenScaling { Min, View, None };
enum class Lobe { All, Diffuse, Specular, Sheen, Clearcoat };
// Whose BRDF is evaluated: the ratified specs, or one engine's maths (docs/profiles.md).
enum class Profile { Spec, Khronos, Threejs, Filament, Babylon, Materialx };
inline constexpr Profile kAllProfiles[] = {Profile::Spec,     Profile::Khronos, Profile::Threejs,
                                           Profile::Filament, Profile::Babylon, Profile::Materialx};

struct EvalOptions {
  SheenVisibility sheenVisibility = SheenVisibility::Charlie;
  SheenDistribution sheenDistribution = SheenDistribution::Charlie;
  SheenScaling sheenScaling = SheenScaling::Min;
  Lobe lobe = Lobe::All;
  Profile profile = Profile::Spec;
};

// Parsing and printing of the option values, as the CLI spells them ("charlie", "min", ...).
// parse* throw brdfcl::Error naming the option and the accepted values.
SheenVisibility parseSheenVisibility(const std::string& s);
SheenDistribution parseSheenDistribution(const std::string& s);
SheenScaling parseSheenScaling(const std::string& s);
Lobe parseLobe(const std::string& s);
Profile parseProfile(const std::string& s, const char* option = "--profile");  // option: named in the message
const char* toString(SheenVisibility v);
const char* toString(SheenDistribution d);
const char* toString(SheenScaling s);
const char* toString(Lobe l);
const char* toString(Profile p);

}  // namespace brdfcl
