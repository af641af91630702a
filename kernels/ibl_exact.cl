/* Ground-truth image-based light (--ibl exact): per covered G-buffer pixel, a Monte Carlo estimate
   of the integral of environment radiance x the layered f (brdf/material.h, as batch evaluation) x
   N.L, by one-sample multiple importance sampling over a mixture of the environment's luminance
   CDF and the BRDF's lobes: the very samplers, pdfs and lobe probabilities of `brdfcl sample`
   (sample.cl, brdf/sampling.h), exact Charlie and Ashikhmin sheen samplers included. Launched in
   chunks of samples; running sums persist. */
#define BRDFCL_W 1
#include "sample.cl"
#include "common/environment.h"
#include "common/gbuffer_pixel.h"

/* The samples of a pixel are REPLICATES independently rotated copies of the sequence (sample k
   is point k / REPLICATES of copy k % REPLICATES): the spread of the copies' means measures the
   error of this quasi-random estimate, which the sample variance (made for independent samples)
   overstates many times. Accumulator planes, np floats each: RGB sums of whole blocks of BLOCK
   samples and of the current block (a single float running sum of 65536 samples drifts by
   ~0.4 %, two levels keep it near 1e-5), then each copy's luminance sums likewise. Blocks follow
   the global sample index, so any chunking of the launches performs the same float operations. */
#define REPLICATES 4
enum { ACC_R, ACC_G, ACC_B, ACC_BLOCK_R, ACC_BLOCK_G, ACC_BLOCK_B, ACC_LUM, ACC_BLOCK_LUM = ACC_LUM + REPLICATES,
       ACC_PLANES = ACC_BLOCK_LUM + REPLICATES };
#define BLOCK 256

/* The techniques are sample.cl's lobes in its order, then the environment. */
enum { TECH_DIFFUSE, TECH_SPECULAR, TECH_SHEEN, TECH_COAT, TECH_UNIFORM, TECH_ENV, TECH_COUNT };
typedef char techniques_follow_the_lobes[(TECH_ENV == LOBE_COUNT && TECH_UNIFORM == LOBE_UNIFORM &&
                                          TECH_COAT == LOBE_COAT) ? 1 : -1];

/* A 32-bit integer mix (xor-shift / multiply rounds) for the per-pixel scramble. */
static inline uint hash_u32(uint x) {
  x ^= x >> 16;
  x *= 0x7feb352du;
  x ^= x >> 15;
  x *= 0x846ca68bu;
  x ^= x >> 16;
  return x;
}

/* Roberts' R2 sequence (the 2-D Kronecker lattice of the plastic number g, g^3 = g + 1, alphas
   1/g and 1/g^2) in 32-bit fixed point, so that sample k is exact for every k, with a per-pixel
   Cranley-Patterson rotation from the hash: reproducible bit for bit and independent between
   pixels. The technique is chosen by the first coordinate, which is then rescaled within the
   chosen interval and reused: a third lattice dimension for the choice instead correlates with
   the direction and leaves mixtures of two lobes converging barely faster than random. */
static inline float r2_dim(uint k, uint alpha, uint rotation) {
  uint x = rotation + k * alpha;
  return (float)(x >> 8) * (1.0f / 16777216.0f);
}

static inline float luminance(float3 c) { return 0.2126f * c.x + 0.7152f * c.y + 0.0722f * c.z; }

/* Direction of equirectangular (u, v): the inverse of env_uv (common/environment.h). */
static inline float3 env_direction(float u, float v, float rotation) {
  float phi = (u - 0.5f) * 2.0f * M_PI_F - rotation, theta = v * M_PI_F;
  float st = sin(theta);
  return (float3)(st * sin(phi), cos(theta), -st * cos(phi));
}

/* The environment's density in solid angle: texel probability x w h / (2 pi^2 sin theta), the
   sin theta being the equirectangular map's area Jacobian. */
static inline float env_pdf(__global const float* texel_p, int w, int h, float3 L, float rotation) {
  float2 uv = env_uv(L, rotation);
  int x = min((int)(uv.x * (float)w), w - 1), y = min((int)(uv.y * (float)h), h - 1);
  float sin_theta = sqrt(max(1.0f - L.y * L.y, 0.0f));
  return texel_p[y * w + x] * (float)(w * h) / (2.0f * M_PI_F * M_PI_F * max(sin_theta, 1e-6f));
}

/* First i with cdf[i + 1] > u, in a CDF of n + 1 entries from 0 to 1. */
static inline int cdf_find(__global const float* cdf, int n, float u) {
  int lo = 0, hi = n - 1;
  while (lo < hi) {
    int mid = (lo + hi) >> 1;
    if (cdf[mid + 1] <= u) lo = mid + 1; else hi = mid;
  }
  return lo;
}

static inline float3 env_sample_direction(__global const float* rows, __global const float* cols, int w, int h,
                                          float u1, float u2, float rotation) {
  int y = cdf_find(rows, h, u1);
  float r0 = rows[y], r1 = rows[y + 1];
  float fy = r1 > r0 ? clamp((u1 - r0) / (r1 - r0), 0.0f, 0.99999994f) : 0.5f;
  __global const float* c = cols + y * (w + 1);
  int x = cdf_find(c, w, u2);
  float c0 = c[x], c1 = c[x + 1];
  float fx = c1 > c0 ? clamp((u2 - c0) / (c1 - c0), 0.0f, 0.99999994f) : 0.5f;
  return env_direction(((float)x + fx) / (float)w, ((float)y + fy) / (float)h, rotation);
}

static inline float3 from_frame(vec3w l, float3 t, float3 b, float3 n) { return l.x * t + l.y * b + l.z * n; }
static inline vec3w lanes3(float3 v) { vec3w o = {v.x, v.y, v.z}; return o; }

/* Technique probabilities: the environment's share comes from the host (large for a peaked
   environment such as a sun, 0 for a uniform one, where BRDF sampling alone is best); the rest
   is split between the lobes as `brdfcl sample` splits it at this view (sample.cl). */
static inline void technique_probabilities(const material_lanes m, float NdotV, __global const float* sheen_e,
                                           int sheen_e_size, float p_env, float* p, float* cdf) {
  float plobe[LOBE_COUNT];
  lobe_probabilities(m, NdotV, sheen_e, sheen_e_size, plobe);
  float run = 0.0f;
  for (int t = 0; t < TECH_ENV; ++t) {
    p[t] = (1.0f - p_env) * plobe[t];
    run += p[t];
    cdf[t] = run;
  }
  p[TECH_ENV] = p_env;
  cdf[TECH_ENV] = 1.0f;
}

/* The technique whose interval of the CDF holds u1; u1 rescaled to [0, 1) within it. A share
   left by float rounding above the last lobe goes to the cosine hemisphere (always present) when
   the environment has none. */
static inline int choose_technique(const float* p, const float* cdf, float p_env, float* u1) {
  int tech = 0;
  while (tech < TECH_ENV && !(*u1 < cdf[tech] && p[tech] > 0.0f)) ++tech;
  if (tech == TECH_ENV && p_env <= 0.0f) {
    tech = TECH_DIFFUSE;
    *u1 = 0.5f;
  } else {
    float lo = cdf[tech] - p[tech];
    *u1 = clamp((*u1 - lo) / p[tech], 0.0f, 0.99999994f);
  }
  return tech;
}

/* The running sums of a pixel (the ACC_ planes): those of the earlier launches, or zeros for the first. */
static inline void acc_load(__global const float* restrict acc, int np, int i, int sample_begin, float3* total,
                            float3* block, float* lum_total, float* lum_block) {
  *total = (float3)(0.0f);
  *block = (float3)(0.0f);
  for (int r = 0; r < REPLICATES; ++r) lum_total[r] = lum_block[r] = 0.0f;
  if (sample_begin > 0) {
    *total = (float3)(acc[ACC_R * np + i], acc[ACC_G * np + i], acc[ACC_B * np + i]);
    *block = (float3)(acc[ACC_BLOCK_R * np + i], acc[ACC_BLOCK_G * np + i], acc[ACC_BLOCK_B * np + i]);
    for (int r = 0; r < REPLICATES; ++r) {
      lum_total[r] = acc[(ACC_LUM + r) * np + i];
      lum_block[r] = acc[(ACC_BLOCK_LUM + r) * np + i];
    }
  }
}

static inline void acc_store(__global float* restrict acc, int np, int i, float3 total, float3 block,
                             const float* lum_total, const float* lum_block) {
  acc[ACC_R * np + i] = total.x; acc[ACC_G * np + i] = total.y; acc[ACC_B * np + i] = total.z;
  acc[ACC_BLOCK_R * np + i] = block.x; acc[ACC_BLOCK_G * np + i] = block.y; acc[ACC_BLOCK_B * np + i] = block.z;
  for (int r = 0; r < REPLICATES; ++r) {
    acc[(ACC_LUM + r) * np + i] = lum_total[r];
    acc[(ACC_BLOCK_LUM + r) * np + i] = lum_block[r];
  }
}

__kernel void ibl_exact(__global const float* restrict gb, int width, int height, brdfcl_camera cam,
                        __global const float* restrict env, int env_w, int env_h, float env_rotation,
                        __global const float* restrict env_rows, __global const float* restrict env_cols,
                        __global const float* restrict env_texel_p, float env_share,
                        __global const float* restrict sheen_e, int sheen_e_size, uint seed, int sample_begin, int sample_end,
                        __global float* restrict acc) {
  int x = get_global_id(0), y = get_global_id(1);
  if (x >= width || y >= height) return;
  const int np = width * height, i = y * width + x;
  if (gb[GB_MASK * np + i] < 0.5f) return;
  const float3 eye = (float3)(cam.position[0], cam.position[1], cam.position[2]);
  const float3 forward = (float3)(cam.forward[0], cam.forward[1], cam.forward[2]);
  const float3 Vg = (float3)(gb[GB_VX * np + i], gb[GB_VY * np + i], gb[GB_VZ * np + i]);
  gbuffer_pixel px = gbuffer_pixel_decode(gb, np, i, Vg, eye, forward, cam.orthographic > 0.5f);
  brdfcl_material packed = brdfcl_pack_material(px.q);
  material_lanes m = material_splat_private(&packed);
  const float3 N = px.N, V = px.V;
  /* V on N's frame (the anisotropic lobe turns it by the anisotropy rotation itself) and on the coat's. */
  const vec3w Vb = lanes3(frame_local(V, px.T, px.B, N));
  const vec3w Vc = lanes3(frame_local(V, px.Tc, px.Bc, px.Nc));
  const float NdotV = dot(N, V);

  const float p_env = env_share;
  float p[TECH_COUNT], cdf[TECH_COUNT];
  technique_probabilities(m, NdotV, sheen_e, sheen_e_size, p_env, p, cdf);

  const uint scramble = hash_u32((uint)i * 0x9e3779b9u + 0x632be5abu + hash_u32(seed));
  uint rot1[REPLICATES], rot2[REPLICATES];
  for (int r = 0; r < REPLICATES; ++r) {
    rot1[r] = hash_u32(scramble ^ (2u * (uint)r + 1u));
    rot2[r] = hash_u32(scramble ^ (2u * (uint)r + 2u));
  }

  float3 total, block;
  float lum_total[REPLICATES], lum_block[REPLICATES];
  acc_load(acc, np, i, sample_begin, &total, &block, lum_total, lum_block);
  for (int k = sample_begin; k < sample_end; ++k) {
    const int rep = k % REPLICATES;
    const uint j = (uint)(k / REPLICATES);
    float u1 = r2_dim(j, 3242174889u, rot1[rep]), u2 = r2_dim(j, 2447445414u, rot2[rep]);
    const int tech = choose_technique(p, cdf, p_env, &u1);
    /* The coat samples in its own frame (its normal may differ from N); the other lobes in N's. */
    float3 L;
    if (tech == TECH_COAT) {
      L = from_frame(lobe_sample(LOBE_COAT, m, Vc, u1, u2), px.Tc, px.Bc, px.Nc);
    } else if (tech < TECH_ENV) {
      L = from_frame(lobe_sample(tech, m, Vb, u1, u2), px.T, px.B, N);
    } else {
      L = env_sample_direction(env_rows, env_cols, env_w, env_h, u1, u2, env_rotation);
    }
    L = normalize(L);
    float3 value = (float3)(0.0f);
    float NdotL = dot(N, L);
    if (NdotL > 0.0f && NdotV > 0.0f) {
      vec3w Lb = lanes3(frame_local(L, px.T, px.B, N));
      vec3w Lc = lanes3(frame_local(L, px.Tc, px.Bc, px.Nc));
      /* One-sample MIS with the balance heuristic: the sample is weighted by the whole mixture's
         density, sum over techniques t of p_t pdf_t(L) (Veach 1997, section 9.2.4). */
      float pdf = (p_env > 0.0f ? p_env * env_pdf(env_texel_p, env_w, env_h, L, env_rotation) : 0.0f);
      for (int t = 0; t < TECH_ENV; ++t)
        if (p[t] > 0.0f) pdf += p[t] * (t == TECH_COAT ? lobe_pdf(LOBE_COAT, m, Lc, Vc) : lobe_pdf(t, m, Lb, Vb));
      if (pdf > 0.0f) {
        /* f exactly as the shade kernel's punctual lights evaluate it: base and sheen on N, the
           clearcoat layered on its own normal. */
        rgbw f = brdf_sheened(m, Lb, Vb, sheen_e, sheen_e_size);
        f = layer_clearcoat(f, m.clearcoat, m.clearcoat_alpha, Lc, Vc);
        float3 Le = env_bilinear(env, env_w, env_h, env_uv(L, env_rotation));
        value = (float3)(f.r, f.g, f.b) * Le * (NdotL / pdf);
        if (!(isfinite(value.x) && isfinite(value.y) && isfinite(value.z))) value = (float3)(0.0f);
      }
    }
    block += value;
    lum_block[rep] += luminance(value);
    if ((k + 1) % BLOCK == 0) {
      total += block;
      block = (float3)(0.0f);
      for (int r = 0; r < REPLICATES; ++r) {
        lum_total[r] += lum_block[r];
        lum_block[r] = 0.0f;
      }
    }
  }
  acc_store(acc, np, i, total, block, lum_total, lum_block);
}
