// glTF parameters -> brdfcl_material: every per-material quantity (alphas, rotation, sheen
// weights) is decoded once here rather than per sample on the device.
#include "model/pack.hpp"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstddef>
#include <type_traits>

#include <fmt/format.h>

#include "brdfcl/error.hpp"
#include "io/option_style.hpp"
#include "model/gltf_material.hpp"
// Last: the kernels' C++ shim (common/host_compat.h) defines OpenCL names for what follows only.
#include "kernels/common/material_pack.h"

namespace brdfcl {

static_assert(std::is_standard_layout_v<brdfcl_material> && std::is_trivially_copyable_v<brdfcl_material>);
static_assert(sizeof(brdfcl_material) == 24 * sizeof(float), "the kernels index materials as 96-byte records");
static_assert(offsetof(brdfcl_material, metallic) == 12);
static_assert(offsetof(brdfcl_material, alpha) == 16);
static_assert(offsetof(brdfcl_material, sheen_color) == 32);
static_assert(offsetof(brdfcl_material, flags) == 60);
static_assert(offsetof(brdfcl_material, clearcoat_alpha) == 68);
static_assert(offsetof(brdfcl_material, sheen_e_row) == 88);

namespace {
float max3(const Rgb& c) { return std::max({c[0], c[1], c[2]}); }

}  // namespace

// The reader's own table and messages (model/gltf_material.cpp), for MaterialParams a caller made.
void checkMaterial(const MaterialParams& m, std::size_t index) { detail::checkMaterialFactors(m, index); }

brdfcl_material packMaterial(const MaterialParams& m, Profile profile) {
  brdfcl_material_params q{};
  for (int i = 0; i < 3; ++i) {
    q.base_color[i] = m.baseColor[i];
    q.sheen_color[i] = m.draftSheen ? m.draftColor[i] * m.draftIntensity : m.sheenColor[i];
  }
  q.metallic = m.metallic;
  q.roughness = m.roughness;
  q.sheen_roughness = m.sheenRoughness;
  q.draft = m.draftSheen ? 1 : 0;
  q.clearcoat = m.clearcoat;
  q.clearcoat_roughness = m.clearcoatRoughness;
  q.anisotropy_strength = m.anisotropyStrength;
  q.anisotropy_rotation = m.anisotropyRotation;
  q.anisotropy = m.anisotropyExtension || m.anisotropyStrength > 0.0f;
  q.ior = m.ior;
  return brdfcl_pack_material_profile(q, profileDefine(profile));
}

int profileDefine(Profile p) {
  switch (p) {
    case Profile::Spec: return BRDFCL_PROFILE_SPEC;
    case Profile::Khronos: return BRDFCL_PROFILE_KHRONOS;
    case Profile::Threejs: return BRDFCL_PROFILE_THREEJS;
    case Profile::Filament: return BRDFCL_PROFILE_FILAMENT;
    case Profile::Babylon: return BRDFCL_PROFILE_BABYLON;
    case Profile::Materialx: return BRDFCL_PROFILE_MATERIALX;
  }
  return BRDFCL_PROFILE_SPEC;
}

void checkProfileOptions(const EvalOptions& o) {
  // An engine profile evaluates its engine's sheen; the spec's sheen variants do not apply to it.
  const EvalOptions defaults;
  const char* option = o.sheenVisibility != defaults.sheenVisibility       ? "--sheen-visibility"
                       : o.sheenDistribution != defaults.sheenDistribution ? "--sheen-distribution"
                       : o.sheenScaling != defaults.sheenScaling           ? "--sheen-scaling"
                                                                           : nullptr;
  if (o.profile != Profile::Spec && option)
    throw Error(fmt::format("{} applies to {} only; {} uses its engine's own sheen (docs/profiles.md)",
                            optionName(option), optionWithValue("--profile", "spec", true),
                            optionWithValue("--profile", toString(o.profile), true)));
}

bool FeatureSet::needsSheenAlbedo(const EvalOptions& o) const {
  switch (o.profile) {
    case Profile::Spec: return ratifiedSheen && o.sheenScaling != SheenScaling::None;
    case Profile::Filament:
    case Profile::Babylon: return ratifiedSheen;
    case Profile::Khronos:   // the renderer's own lut_sheen_E.png (engine_tables.hpp)
    case Profile::Threejs:
    case Profile::Materialx: return false;  // analytic albedo fits
  }
  return false;
}

EvalOptions sheenTableOptions(const EvalOptions& o) {
  EvalOptions t = o;
  if (o.profile == Profile::Spec) return t;
  t.sheenDistribution = SheenDistribution::Charlie;
  // Khronos: E of its own lobe (Conty-Kulla V); Filament's DFG.z and Babylon's env-BRDF .b
  // integrate Charlie D with the Neubelt (Ashikhmin) V.
  t.sheenVisibility = o.profile == Profile::Khronos ? SheenVisibility::Charlie : SheenVisibility::Ashikhmin;
  t.sheenScaling = SheenScaling::Min;
  return t;
}

FeatureSet featuresOf(const std::vector<MaterialParams>& materials, Profile profile) {
  FeatureSet f;
  for (const auto& m : materials) {
    const bool sheen = m.draftSheen ? (m.draftIntensity > 0.0f && max3(m.draftColor) > 0.0f) : max3(m.sheenColor) > 0.0f;
    f.sheen |= sheen;
    f.draft |= sheen && m.draftSheen;
    f.ratifiedSheen |= sheen && !m.draftSheen;
    f.clearcoat |= m.clearcoat > 0.0f;
    // khronos and filament take their anisotropic paths whenever the extension is present.
    f.anisotropy |= m.anisotropyStrength > 0.0f ||
                    ((profile == Profile::Khronos || profile == Profile::Filament) && m.anisotropyExtension);
  }
  return f;
}

std::string materialDefines(const EvalOptions& o, const FeatureSet& f) {
  auto lobe = [&] {
    switch (o.lobe) {
      case Lobe::All: return BRDFCL_LOBE_ALL;
      case Lobe::Diffuse: return BRDFCL_LOBE_DIFFUSE;
      case Lobe::Specular: return BRDFCL_LOBE_SPECULAR;
      case Lobe::Sheen: return BRDFCL_LOBE_SHEEN;
      case Lobe::Clearcoat: return BRDFCL_LOBE_CLEARCOAT;
    }
    return BRDFCL_LOBE_ALL;
  }();
  const int scaling = o.sheenScaling == SheenScaling::Min    ? BRDFCL_SCALING_MIN
                      : o.sheenScaling == SheenScaling::View ? BRDFCL_SCALING_VIEW
                                                             : BRDFCL_SCALING_NONE;
  // No engine reads the draft sheen (docs/profiles.md).
  const bool spec = o.profile == Profile::Spec;
  // Spec's options text stays exactly what it was, so its programs (and cache keys) are unchanged.
  const std::string profile =
      o.profile == Profile::Spec ? std::string() : fmt::format(" -DBRDFCL_PROFILE={}", profileDefine(o.profile));
  return fmt::format(
      "-DBRDFCL_SHEEN_VIS={} -DBRDFCL_SHEEN_DIST={} -DBRDFCL_SCALING={} -DBRDFCL_LOBE={} -DBRDFCL_HAS_SHEEN={} "
      "-DBRDFCL_HAS_DRAFT={} -DBRDFCL_HAS_CLEARCOAT={} -DBRDFCL_HAS_ANISOTROPY={}{}",
      o.sheenVisibility == SheenVisibility::Ashikhmin ? BRDFCL_SHEEN_VIS_ASHIKHMIN : BRDFCL_SHEEN_VIS_CHARLIE,
      o.sheenDistribution == SheenDistribution::Ashikhmin ? BRDFCL_SHEEN_DIST_ASHIKHMIN : BRDFCL_SHEEN_DIST_CHARLIE,
      scaling, lobe, int(spec ? f.sheen : f.ratifiedSheen), int(spec && f.draft), int(f.clearcoat),
      int(f.anisotropy), profile);
}

}  // namespace brdfcl
