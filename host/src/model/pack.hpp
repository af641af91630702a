// Decoding of glTF material parameters into the packed layout the kernels read
// (kernels/common/material_layout.h), and the compile-time feature set of a batch.
#pragma once
#include <cstddef>
#include <string>
#include <vector>

#include "brdfcl/material.hpp"
#include "kernels/common/material_layout.h"

namespace brdfcl {

// Decoded as `profile`'s engine decodes it (docs/profiles.md); Spec is brdfcl's own decode.
brdfcl_material packMaterial(const MaterialParams& m, Profile profile = Profile::Spec);
// Throws brdfcl::Error when an engine profile is combined with a spec-only sheen option
// ("--sheen-visibility applies to --profile spec only; ...").
void checkProfileOptions(const EvalOptions& o);
// The BRDFCL_PROFILE_* value of a profile.
int profileDefine(Profile p);

// Throws brdfcl::Error ("material 3: roughness must be a number in [0, 1], got nan") unless
// every field lies in the glTF schema domain that readMaterials enforces for files: NaN or an
// infinity would otherwise reach the kernels and come back as NaN f without a word.
void checkMaterial(const MaterialParams& m, std::size_t index);

// Which layers any material of the batch uses; unused ones are compiled out.
struct FeatureSet {
  bool sheen = false, draft = false, clearcoat = false, anisotropy = false;
  bool needsSheenAlbedo(const EvalOptions& o) const;
  bool ratifiedSheen = false;
};
FeatureSet featuresOf(const std::vector<MaterialParams>& materials, Profile profile = Profile::Spec);

// The options whose sheen E table a batch reads: the user's under Spec; under an engine profile
// the table that engine's sheen scaling uses (docs/profiles.md "Tables"). Lobe and profile kept.
EvalOptions sheenTableOptions(const EvalOptions& o);

// The -D options for kernels/brdf/material.h.
std::string materialDefines(const EvalOptions& o, const FeatureSet& f);

}  // namespace brdfcl
