// GLSL on GLM: the types, built-ins and qualifiers an engine's shader functions need so that
// scripts/engine-check can compile them as C++ (literals already carry an `f`, swizzles are calls).
// Everything stays in float, as on a GPU (EC_FLOAT64: in double, to tell an engine's own float
// rounding from a real difference); nothing here is engine code.
#pragma once
#define GLM_FORCE_SWIZZLE
#include <glm/glm.hpp>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

#ifdef EC_FLOAT64
using real = double;
#else
using real = float;
#endif
using vec2 = glm::vec<2, real, glm::defaultp>;
using vec3 = glm::vec<3, real, glm::defaultp>;
using vec4 = glm::vec<4, real, glm::defaultp>;
using mat2 = glm::mat<2, 2, real, glm::defaultp>;
using mat3 = glm::mat<3, 3, real, glm::defaultp>;
using mat4 = glm::mat<4, 4, real, glm::defaultp>;
using glm::ivec2; using glm::ivec3; using glm::ivec4;
using glm::dot; using glm::cross; using glm::normalize; using glm::length; using glm::distance;
using glm::reflect; using glm::refract;
using glm::clamp; using glm::mix; using glm::min; using glm::max; using glm::abs; using glm::sign;
using glm::floor; using glm::ceil; using glm::fract; using glm::mod; using glm::step; using glm::smoothstep;
using glm::pow; using glm::exp; using glm::exp2; using glm::log; using glm::log2; using glm::sqrt;
using glm::inversesqrt; using glm::sin; using glm::cos; using glm::tan; using glm::asin; using glm::acos; using glm::atan;

// Scalar forms GLM lacks (<cmath> already gives pow, exp, log, sqrt, abs).
inline real inversesqrt(real a) { return real(1) / std::sqrt(a); }
inline real sign(real a) { return a > real(0) ? real(1) : (a < real(0) ? -real(1) : real(0)); }
inline real fract(real a) { return a - std::floor(a); }
inline real saturate(real a) { return glm::clamp(a, real(0), real(1)); }
inline vec2 saturate(vec2 a) { return glm::clamp(a, real(0), real(1)); }
inline vec3 saturate(vec3 a) { return glm::clamp(a, real(0), real(1)); }
inline vec4 saturate(vec4 a) { return glm::clamp(a, real(0), real(1)); }
// GLSL's mix/clamp/min/max with an int where a float is meant.
inline real mix(real a, real b, real t) { return a + (b - a) * t; }
inline real clamp(real x, real lo, real hi) { return std::fmin(std::fmax(x, lo), hi); }
inline real min(real a, real b) { return b < a ? b : a; }
inline real max(real a, real b) { return a < b ? b : a; }
inline real atan(real y, real x) { return std::atan2(y, x); }

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
  if (s.w == 0) return vec4(real(0));
  real x = uv.x * real(s.w) - real(0.5), y = uv.y * real(s.h) - real(0.5);
  real x0 = std::floor(x), y0 = std::floor(y), fx = x - x0, fy = y - y0;
  int i = int(x0), j = int(y0);
  real a = mix(s.at(i, j), s.at(i + 1, j), fx), b = mix(s.at(i, j + 1), s.at(i + 1, j + 1), fx);
  return vec4(mix(a, b, fy), real(0), real(0), real(1));
}
inline vec4 textureLod(const sampler2D& s, vec2 uv, real) { return texture(s, uv); }

// A swizzle written to (`c.rgb *= k`, `v.xy = w`): GLM's swizzle calls return copies, so the
// converter spells these ec::swz<N>(c, i...) OP rhs, which writes the named components.
namespace ec {
template <int N, class V>
struct Swz {
  V& v;
  int i[N];
  using T = glm::vec<N, real, glm::defaultp>;
  template <class R> Swz& operator=(const R& r) { T t(r); for (int k = 0; k < N; ++k) v[i[k]] = t[k]; return *this; }
  template <class R> Swz& operator+=(const R& r) { T t(r); for (int k = 0; k < N; ++k) v[i[k]] += t[k]; return *this; }
  template <class R> Swz& operator-=(const R& r) { T t(r); for (int k = 0; k < N; ++k) v[i[k]] -= t[k]; return *this; }
  template <class R> Swz& operator*=(const R& r) { T t(r); for (int k = 0; k < N; ++k) v[i[k]] *= t[k]; return *this; }
  template <class R> Swz& operator/=(const R& r) { T t(r); for (int k = 0; k < N; ++k) v[i[k]] /= t[k]; return *this; }
};
template <int N, class V, class... I> inline Swz<N, V> swz(V& v, I... idx) { return Swz<N, V>{v, {int(idx)...}}; }
}  // namespace ec

// Screen-space derivatives of a flat, front-facing quad whose UVs follow +X and +Y: the engine's
// own tangent-frame code then builds N = +Z, T = +X, B = +Y.
inline vec2 dFdx(vec2) { return vec2(1, 0); }
inline vec2 dFdy(vec2) { return vec2(0, 1); }
inline vec3 dFdx(vec3) { return vec3(1, 0, 0); }
inline vec3 dFdy(vec3) { return vec3(0, 1, 0); }
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
    if (ec::g_lobe != ec::ALL && ec::g_lobe != (LOBE)) return R(0);                 \
    ec::Ctx c(LOBE);                                                                   \
    return NAME##__engine(a...);                                                       \
  }

// As EC_LOBE_HOOK, for a lobe whose out-parameters feed the other lobes (a coat's Fresnel weight):
// it always runs, and a run that does not keep LOBE gets 0 from its return value only.
#define EC_LOBE_HOOK_LAYER(NAME, LOBE)                                                 \
  template <class... A>                                                                \
  inline auto NAME(A&&... a) -> decltype(NAME##__engine(a...)) {                       \
    using R = decltype(NAME##__engine(a...));                                          \
    if (ec::g_ctx != 0) return NAME##__engine(a...);                                   \
    ec::Ctx c(LOBE);                                                                   \
    R r = NAME##__engine(a...);                                                        \
    return ec::g_lobe != ec::ALL && ec::g_lobe != (LOBE) ? R(0) : r;                   \
  }
