// glTF parameters -> brdfcl_material: every per-material quantity (alphas, rotation, sheen
// weights) is decoded once here rather than per sample on the device.
#include "model/pack.hpp"

#include "kernels/common/material_pack.h"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <type_traits>

#include <fmt/format.h>

namespace brdfcl {

static_assert(std::is_standard_layout_v<brdfcl_material> && std::is_trivially_copyable_v<brdfcl_material>);
static_assert(sizeof(brdfcl_material) == 24 * sizeof(float), "the kernels index materials as 96-byte records");
static_assert(offsetof(brdfcl_material, metallic) == 12);
static_assert(offsetof(brdfcl_material, alpha) == 16);
static_assert(offsetof(brdfcl_material, sheen_color) == 32);
static_assert(offsetof(brdfcl_material, flags) == 60);
static_assert(offsetof(brdfcl_material, clearcoat_alpha) == 68);

namespace {
float max3(const Rgb& c) { return std::max({c[0], c[1], c[2]}); }
}  // namespace

brdfcl_material packMaterial(const MaterialParams& m) {
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
  return brdfcl_pack_material(q);
}

FeatureSet featuresOf(const std::vector<MaterialParams>& materials) {
  FeatureSet f;
  for (const auto& m : materials) {
    const bool sheen = m.draftSheen ? (m.draftIntensity > 0.0f && max3(m.draftColor) > 0.0f) : max3(m.sheenColor) > 0.0f;
    f.sheen |= sheen;
    f.draft |= sheen && m.draftSheen;
    f.ratifiedSheen |= sheen && !m.draftSheen;
    f.clearcoat |= m.clearcoat > 0.0f;
    f.anisotropy |= m.anisotropyStrength > 0.0f;
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
  return fmt::format(
      "-DBRDFCL_SHEEN_VIS={} -DBRDFCL_SHEEN_DIST={} -DBRDFCL_SCALING={} -DBRDFCL_LOBE={} -DBRDFCL_HAS_SHEEN={} "
      "-DBRDFCL_HAS_DRAFT={} -DBRDFCL_HAS_CLEARCOAT={} -DBRDFCL_HAS_ANISOTROPY={}",
      o.sheenVisibility == SheenVisibility::Ashikhmin ? BRDFCL_SHEEN_VIS_ASHIKHMIN : BRDFCL_SHEEN_VIS_CHARLIE,
      o.sheenDistribution == SheenDistribution::Ashikhmin ? BRDFCL_SHEEN_DIST_ASHIKHMIN : BRDFCL_SHEEN_DIST_CHARLIE,
      scaling, lobe, int(f.sheen), int(f.draft), int(f.clearcoat), int(f.anisotropy));
}

}  // namespace brdfcl
