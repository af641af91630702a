/* The packed material and the sample/options constants that cross the host/device boundary.
   Included verbatim by the host C++ (host/src/model/pack.cpp, which static_asserts the layout)
   and by every OpenCL kernel. Everything here is 4-byte scalars, so both sides agree on offsets. */
#ifndef BRDFCL_MATERIAL_LAYOUT_H
#define BRDFCL_MATERIAL_LAYOUT_H

#ifdef __OPENCL_VERSION__
typedef uint brdfcl_u32;
#else
#include <cstdint>
typedef std::uint32_t brdfcl_u32;
#endif

/* Material flags. */
#define BRDFCL_MAT_SHEEN 1u       /* a sheen lobe is present (max3(sheenColor) > 0) */
#define BRDFCL_MAT_DRAFT_SHEEN 2u /* the experimental draft's additive (1 - reflectance) blend */
#define BRDFCL_MAT_ANISOTROPY 4u  /* khronos, filament: KHR_materials_anisotropy is present, whatever its strength */

/* A glTF material decoded once on the host: alphas squared and clamped, the anisotropic
   tangent rotation as cos/sin, sheen weights folded in. 24 floats = 96 bytes. */
typedef struct brdfcl_material {
  float base_color[3];
  float metallic;
  float alpha;           /* roughness^2, clamped to BRDFCL_MIN_ALPHA: bitangent alpha of anisotropy */
  float alpha_t;         /* mix(alpha, 1, anisotropyStrength^2): alpha along the rotated tangent */
  float aniso_cos;       /* cos(anisotropyRotation) */
  float aniso_sin;       /* sin(anisotropyRotation) */
  float sheen_color[3];  /* ratified: sheenColorFactor; draft: colorFactor * intensityFactor */
  float sheen_max;       /* max3 of the ratified sheen color, for albedo scaling */
  float sheen_alpha;     /* sheenRoughness^2 (draft: roughness^2), clamped to BRDFCL_MIN_SHEEN_ALPHA */
  float sheen_roughness; /* E-table coordinate: sheenRoughness as given */
  float sheen_weight;    /* ratified: 1; draft: 1 - max3(mix(0.04, baseColor, metallic)) */
  brdfcl_u32 flags;
  float clearcoat;
  float clearcoat_alpha; /* clearcoatRoughness^2, clamped to BRDFCL_MIN_ALPHA */
  /* Read by the engine profiles only (docs/profiles.md); spec's kernels never load them. */
  float roughness;       /* the profile's perceptual base roughness (DFG table coordinate) */
  float ior_f0;          /* dielectric F0 from KHR_materials_ior, as the profile derives it */
  float aniso_strength;  /* anisotropyStrength */
  float clearcoat_roughness; /* the profile's perceptual coat roughness (DFG table coordinate) */
  /* Set per batch by the host (Evaluator::prepare) where the batch's program reads rows of E
     (BRDFCL_E_ROW): where this material's row of the sheen albedo table, blended once for its
     sheen_roughness, starts in the table buffer, in floats. 0 elsewhere. */
  brdfcl_u32 sheen_e_row;
  float reserved;        /* pads the record to 96 bytes */
} brdfcl_material;

/* Clamps, documented in docs/model.md ("Clamps"). Both sit below the alphas of roughness 0.05
   (0.0025), so they never change a result in the range the specs are tested on. */
#define BRDFCL_MIN_ALPHA 1.0e-3f        /* GGX: alpha = 0 is a delta; keeps D finite in float */
#define BRDFCL_MIN_SHEEN_ALPHA 1.0e-3f  /* Charlie: exponent 1/alpha; Ashikhmin: cot^2/alpha^2 */

/* Option values, passed to kernels as -D defines. */
#define BRDFCL_SHEEN_VIS_CHARLIE 0
#define BRDFCL_SHEEN_VIS_ASHIKHMIN 1
#define BRDFCL_SHEEN_DIST_CHARLIE 0
#define BRDFCL_SHEEN_DIST_ASHIKHMIN 1
#define BRDFCL_SCALING_MIN 0
#define BRDFCL_SCALING_VIEW 1
#define BRDFCL_SCALING_NONE 2
#define BRDFCL_LOBE_ALL 0
#define BRDFCL_LOBE_DIFFUSE 1
#define BRDFCL_LOBE_SPECULAR 2
#define BRDFCL_LOBE_SHEEN 3
#define BRDFCL_LOBE_CLEARCOAT 4
#define BRDFCL_PROFILE_SPEC 0
#define BRDFCL_PROFILE_KHRONOS 1
#define BRDFCL_PROFILE_THREEJS 2
#define BRDFCL_PROFILE_FILAMENT 3
#define BRDFCL_PROFILE_BABYLON 4
#define BRDFCL_PROFILE_MATERIALX 5

/* Engine profiles read, after the sheen E table (size^2 floats), three.js's 16x16 DFG table:
   (A, B) per texel, row-major, rows = N.V, columns = roughness (docs/profiles.md). */
#define BRDFCL_DFG_SIZE 16
/* --profile khronos reads, after the DFG table, the Sample Renderer's lut_sheen_E.png: size^2
   floats (unorm8 / 255), rows = sheen roughness, columns = N.V (docs/profiles.md "Tables"). */
#define BRDFCL_KHRONOS_SHEEN_E_SIZE 1024
/* --profile babylon reads, after the DFG table, Babylon's environment BRDF texture: size^2 texels
   of 3 floats (.x = B, .y = A + B, .b = sheen albedo), rows = perceptual roughness, columns = N.V
   (docs/profiles.md "Tables"). */
#define BRDFCL_BABYLON_BRDF_SIZE 256

#endif
