// GLSL on GLM: the types, built-ins and qualifiers an engine's shader functions need so that
// scripts/engine-check can compile them as C++ (literals already carry an `f`, swizzles are calls).
// Everything stays in float, as on a GPU; nothing here is engine code.
#pragma once
#define GLM_FORCE_SWIZZLE
#include <glm/glm.hpp>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

using glm::vec2; using glm::vec3; using glm::vec4;
using glm::ivec2; using glm::ivec3; using glm::ivec4;
using glm::mat2; using glm::mat3; using glm::mat4;
using glm::dot; using glm::cross; using glm::normalize; using glm::length; using glm::distance;
using glm::reflect; using glm::refract;
using glm::clamp; using glm::mix; using glm::min; using glm::max; using glm::abs; using glm::sign;
using glm::floor; using glm::ceil; using glm::fract; using glm::mod; using glm::step; using glm::smoothstep;
using glm::pow; using glm::exp; using glm::exp2; using glm::log; using glm::log2; using glm::sqrt;
using glm::inversesqrt; using glm::sin; using glm::cos; using glm::tan; using glm::asin; using glm::acos; using glm::atan;

// Scalar forms GLM lacks (<cmath> already gives pow, exp, log, sqrt, abs in float).
inline float inversesqrt(float a) { return 1.0f / std::sqrt(a); }
inline float sign(float a) { return a > 0.0f ? 1.0f : (a < 0.0f ? -1.0f : 0.0f); }
inline float fract(float a) { return a - std::floor(a); }
inline float saturate(float a) { return glm::clamp(a, 0.0f, 1.0f); }
inline vec2 saturate(vec2 a) { return glm::clamp(a, 0.0f, 1.0f); }
inline vec3 saturate(vec3 a) { return glm::clamp(a, 0.0f, 1.0f); }
inline vec4 saturate(vec4 a) { return glm::clamp(a, 0.0f, 1.0f); }
// GLSL's mix/clamp/min/max with an int where a float is meant.
inline float mix(float a, float b, float t) { return a + (b - a) * t; }
inline float clamp(float x, float lo, float hi) { return std::fmin(std::fmax(x, lo), hi); }
inline float min(float a, float b) { return b < a ? b : a; }
inline float max(float a, float b) { return a < b ? b : a; }
inline float atan(float y, float x) { return std::atan2(y, x); }

// A 2D float texture sampled the way a GPU does (bilinear, clamp to edge), red channel only.
struct sampler2D {
  int w = 0, h = 0;
  std::vector<float> texels;  // row-major, h rows of w
  float at(int x, int y) const {
    x = x < 0 ? 0 : (x >= w ? w - 1 : x);
    y = y < 0 ? 0 : (y >= h ? h - 1 : y);
    return texels[size_t(y) * size_t(w) + size_t(x)];
  }
};
inline vec4 texture(const sampler2D& s, vec2 uv) {
  if (s.w == 0) return vec4(0.0f);
  float x = uv.x * float(s.w) - 0.5f, y = uv.y * float(s.h) - 0.5f;
  float x0 = std::floor(x), y0 = std::floor(y), fx = x - x0, fy = y - y0;
  int i = int(x0), j = int(y0);
  float a = mix(s.at(i, j), s.at(i + 1, j), fx), b = mix(s.at(i, j + 1), s.at(i + 1, j + 1), fx);
  return vec4(mix(a, b, fy), 0.0f, 0.0f, 1.0f);
}
inline vec4 textureLod(const sampler2D& s, vec2 uv, float) { return texture(s, uv); }

// Screen-space derivatives of a flat, front-facing quad whose UVs follow +X and +Y: the engine's
// own tangent-frame code then builds N = +Z, T = +X, B = +Y.
inline vec2 dFdx(vec2) { return vec2(1.0f, 0.0f); }
inline vec2 dFdy(vec2) { return vec2(0.0f, 1.0f); }
inline vec3 dFdx(vec3) { return vec3(1.0f, 0.0f, 0.0f); }
inline vec3 dFdy(vec3) { return vec3(0.0f, 1.0f, 0.0f); }
static bool gl_FrontFacing = true;

// Which lobe the run keeps: lobe hooks wrap the engine functions that start a lobe.
namespace ec {
enum Lobe { ALL = 0, DIFFUSE = 1, SPECULAR = 2, SHEEN = 3, CLEARCOAT = 4 };
inline int g_lobe = ALL;  // the lobe kept by this run
inline int g_ctx = 0;     // the lobe whose function is running (its callees pass through)
struct Ctx {
  int saved;
  explicit Ctx(int lobe) : saved(g_ctx) { g_ctx = lobe; }
  ~Ctx() { g_ctx = saved; }
};
}  // namespace ec

// Wraps NAME (renamed NAME__engine in the pasted source) as one lobe's entry point: outside
// another lobe's call, a run that does not keep LOBE gets 0 from it.
#define EC_LOBE_HOOK(NAME, LOBE)                                                       \
  template <class... A>                                                                \
  inline auto NAME(A&&... a) -> decltype(NAME##__engine(a...)) {                       \
    using R = decltype(NAME##__engine(a...));                                          \
    if (ec::g_ctx != 0) return NAME##__engine(a...);                                   \
    if (ec::g_lobe != ec::ALL && ec::g_lobe != (LOBE)) return R(0.0f);                 \
    ec::Ctx c(LOBE);                                                                   \
    return NAME##__engine(a...);                                                       \
  }
