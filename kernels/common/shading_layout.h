/* What the shading kernels share with the host: the G-buffer plane order, the punctual light
   and camera records, and the environment's equirectangular mapping. Included verbatim by the
   host (host/src/render/shader.cpp, camera.cpp and spheres_gbuffer.cpp static_assert the
   records) and by kernels/shade.cl. */
#ifndef BRDFCL_SHADING_LAYOUT_H
#define BRDFCL_SHADING_LAYOUT_H

/* G-buffer planes, width * height floats each, in this order. The host fills absent optional
   channels with their defaults: T = 0 (build a frame from N), emissive/sheen/clearcoat/
   anisotropy = 0, clearcoatN = 0 (use N), occlusion = 1, V = 0. A V of zero length is the
   "no V" flag: the pixel's view comes from the camera record (a G-buffer's V is never zero:
   the reader and the host reject it). */
enum {
  GB_PX, GB_PY, GB_PZ, GB_NX, GB_NY, GB_NZ, GB_TX, GB_TY, GB_TZ,
  GB_BASE_R, GB_BASE_G, GB_BASE_B, GB_METALLIC, GB_ROUGHNESS, GB_MASK,
  GB_EMISSIVE_R, GB_EMISSIVE_G, GB_EMISSIVE_B,
  GB_SHEEN_R, GB_SHEEN_G, GB_SHEEN_B, GB_SHEEN_ROUGHNESS,
  GB_CLEARCOAT, GB_CLEARCOAT_ROUGHNESS, GB_CCN_X, GB_CCN_Y, GB_CCN_Z,
  GB_ANISO_STRENGTH, GB_ANISO_ROTATION,
  GB_OCCLUSION, GB_VX, GB_VY, GB_VZ,
  GB_PLANES
};

#define BRDFCL_LIGHT_DIRECTIONAL 0
#define BRDFCL_LIGHT_POINT 1
#define BRDFCL_LIGHT_SPOT 2

/* KHR_lights_punctual light in world space, 16 floats. */
typedef struct brdfcl_light {
  float type;          /* BRDFCL_LIGHT_* */
  float color[3];      /* linear RGB times intensity (lux or candela) */
  float position[3];   /* point, spot */
  float range;         /* 0 = infinite */
  float direction[3];  /* unit, the way the light travels (directional, spot) */
  float cone_scale;    /* spot: 1 / max(1e-3, cos(inner) - cos(outer)) */
  float cone_offset;   /* spot: -cos(outer) * cone_scale */
  float pad[3];
} brdfcl_light;

/* Camera, 16 floats. Pinhole (orthographic 0): a pixel (x + 0.5, y + 0.5) from the top-left looks
   along forward + ((2 (x + 0.5) / w - 1) tan_half_fov aspect) right + ((1 - 2 (y + 0.5) / h)
   tan_half_fov) up. Orthographic (1, a G-buffer's camera): every pixel looks along forward, and
   only that direction matters to shading, so the view's extent is not carried. */
typedef struct brdfcl_camera {
  float position[3], tan_half_fov;
  float right[3], aspect;
  float up[3], orthographic;
  float forward[3], pad1;
} brdfcl_camera;

/* One sphere of the built-in "spheres" scene, 20 floats: geometry and glTF parameters. */
typedef struct brdfcl_sphere {
  float center[3], radius;
  float base_color[3], metallic, roughness;
  float sheen_color[3], sheen_roughness;
  float clearcoat, clearcoat_roughness;
  float anisotropy_strength, anisotropy_rotation;
  float pad[3];
} brdfcl_sphere;

/* Equirectangular environment: direction d (world, +Y up) -> u = 1/2 + atan2(d.x, -d.z) / 2pi
   (+ rotation / 2pi), v = acos(d.y) / pi, v = 0 at the top row. */

/* Prefiltered environments (host/src/render/prefilter.cpp): the GGX chain keeps level 0 (the mirror)
   at the map's size and computes levels >= 1 as for a map of at most CAP_W x CAP_H; the Charlie
   chain (sheen lobes are broad at every roughness) starts from at most CHARLIE_W x CHARLIE_H. */
#define BRDFCL_PREFILTER_CAP_W 512
#define BRDFCL_PREFILTER_CAP_H 256
#define BRDFCL_CHARLIE_W 128
#define BRDFCL_CHARLIE_H 64

/* The anisotropic split-sum table (kernels/aniso_dfg.cl): texels over N.V x perceptual roughness
   x anisotropy strength x view azimuth from the anisotropy direction in [0, pi/2], N.V fastest,
   A and B interleaved. */
#define BRDFCL_ANISO_DFG_NV 32
#define BRDFCL_ANISO_DFG_R 24
#define BRDFCL_ANISO_DFG_S 12
#define BRDFCL_ANISO_DFG_PSI 7

#endif
