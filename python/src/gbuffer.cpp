// brdfcl._core's G-buffers: read and written as EXR through the library, and converted to and
// from a dict of numpy channel arrays (docs/gbuffer.md's channel names) and a camera dict.
#include <nanobind/stl/string.h>
#include <nanobind/stl/vector.h>

#include <array>
#include <cmath>
#include <string>
#include <vector>

#include "bindings.hpp"
#include "brdfcl/error.hpp"
#include "brdfcl/gbuffer.hpp"
#include "brdfcl/render.hpp"
#include "brdfcl/scene.hpp"

using namespace nanobind::literals;

namespace brdfcl_python {
namespace {

using brdfcl::Error;

// G-buffer channels as numpy arrays: (H, W, 3) vectors, (H, W) scalars, canonical names.
struct Channel {
  const char* name;
  std::vector<float> brdfcl::GBuffer::*field;
  int components;
  bool required;
};
const Channel kChannels[] = {
    {"P", &brdfcl::GBuffer::P, 3, true},
    {"N", &brdfcl::GBuffer::N, 3, true},
    {"baseColor", &brdfcl::GBuffer::baseColor, 3, true},
    {"metallic", &brdfcl::GBuffer::metallic, 1, true},
    {"roughness", &brdfcl::GBuffer::roughness, 1, true},
    {"mask", &brdfcl::GBuffer::mask, 1, true},
    {"T", &brdfcl::GBuffer::T, 3, false},
    {"emissive", &brdfcl::GBuffer::emissive, 3, false},
    {"sheenColor", &brdfcl::GBuffer::sheenColor, 3, false},
    {"sheenRoughness", &brdfcl::GBuffer::sheenRoughness, 1, false},
    {"clearcoat", &brdfcl::GBuffer::clearcoat, 1, false},
    {"clearcoatRoughness", &brdfcl::GBuffer::clearcoatRoughness, 1, false},
    {"clearcoatN", &brdfcl::GBuffer::clearcoatN, 3, false},
    {"anisotropyStrength", &brdfcl::GBuffer::anisotropyStrength, 1, false},
    {"anisotropyRotation", &brdfcl::GBuffer::anisotropyRotation, 1, false},
    {"occlusion", &brdfcl::GBuffer::occlusion, 1, false},
    {"V", &brdfcl::GBuffer::V, 3, false},
};

nb::dict gbufferToDict(brdfcl::GBuffer&& g) {
  nb::dict d;
  const auto h = std::size_t(g.height), w = std::size_t(g.width);
  for (const auto& c : kChannels) {
    auto& v = g.*c.field;
    if (v.empty()) continue;
    d[c.name] = c.components == 3 ? toNumpy(std::move(v), {h, w, 3}) : toNumpy(std::move(v), {h, w});
  }
  if (g.camera) {
    const auto& c = *g.camera;
    nb::dict cam;
    cam["orthographic"] = c.orthographic;
    cam["position"] = std::vector<float>(c.position.begin(), c.position.end());
    cam["right"] = std::vector<float>(c.right.begin(), c.right.end());
    cam["up"] = std::vector<float>(c.up.begin(), c.up.end());
    cam["forward"] = std::vector<float>(c.forward.begin(), c.forward.end());
    cam["fov"] = c.fovDegrees;
    cam["xmag"] = c.xmag;
    cam["ymag"] = c.ymag;
    cam["znear"] = c.znear;
    cam["zfar"] = c.zfar;
    d["camera"] = cam;
  }
  return d;
}

std::array<float, 3> vec3(const nb::dict& d, const char* key, std::array<float, 3> fallback) {
  if (!d.contains(key)) return fallback;
  const auto v = nb::cast<std::vector<float>>(d[key]);
  if (v.size() != 3) throw Error(std::string("gbuffer camera: ") + key + " must have 3 numbers");
  return {v[0], v[1], v[2]};
}

// A G-buffer from a dict of channel arrays (float32, C-contiguous: the Python front converts).
brdfcl::GBuffer gbufferFromDict(const nb::dict& d) {
  brdfcl::GBuffer g;
  for (auto [key, value] : d) {
    const std::string name = nb::cast<std::string>(key);
    if (name == "camera") continue;
    bool known = false;
    for (const auto& c : kChannels) known = known || name == c.name;
    if (!known) throw Error("gbuffer: unknown channel '" + name + "'; the channels are docs/gbuffer.md's (P, N, baseColor, ...)");
  }
  for (const auto& c : kChannels) {
    if (!d.contains(c.name)) {
      if (c.required) throw Error(std::string("gbuffer: missing required channel '") + c.name + "'");
      continue;
    }
    auto a = nb::cast<nb::ndarray<const float, nb::c_contig, nb::device::cpu>>(d[c.name], false);
    const bool shapeOk = c.components == 3 ? a.ndim() == 3 && a.shape(2) == 3 : a.ndim() == 2;
    if (!shapeOk)
      throw Error(std::string("gbuffer: channel '") + c.name + "' must have shape " +
                  (c.components == 3 ? "(H, W, 3)" : "(H, W)"));
    const int h = int(a.shape(0)), w = int(a.shape(1));
    if (g.width == 0 && g.height == 0) {
      g.width = w;
      g.height = h;
    } else if (w != g.width || h != g.height) {
      throw Error(std::string("gbuffer: channel '") + c.name + "' is " + std::to_string(h) + "x" + std::to_string(w) +
                  " (HxW), the others " + std::to_string(g.height) + "x" + std::to_string(g.width));
    }
    auto& v = g.*c.field;
    v.assign(a.data(), a.data() + a.size());
    for (std::size_t i = 0; i < v.size(); ++i)
      if (!std::isfinite(v[i]))
        throw Error(std::string("gbuffer: channel '") + c.name + "' holds a NaN or an infinity at element " + std::to_string(i));
  }
  if (g.width == 0 || g.height == 0) throw Error("gbuffer: the channels are empty");
  if (d.contains("camera")) {
    const nb::dict c = nb::cast<nb::dict>(d["camera"]);
    brdfcl::GBufferCamera cam;
    if (c.contains("orthographic")) cam.orthographic = nb::cast<bool>(c["orthographic"]);
    cam.position = vec3(c, "position", cam.position);
    cam.right = vec3(c, "right", cam.right);
    cam.up = vec3(c, "up", cam.up);
    cam.forward = vec3(c, "forward", cam.forward);
    if (c.contains("fov")) cam.fovDegrees = nb::cast<float>(c["fov"]);
    if (c.contains("xmag")) cam.xmag = nb::cast<float>(c["xmag"]);
    if (c.contains("ymag")) cam.ymag = nb::cast<float>(c["ymag"]);
    if (c.contains("znear")) cam.znear = nb::cast<float>(c["znear"]);
    if (c.contains("zfar")) cam.zfar = nb::cast<float>(c["zfar"]);
    g.camera = cam;
  }
  return g;
}

}  // namespace

void bindGbuffer(nb::module_& m) {
  nb::class_<brdfcl::GBuffer>(m, "GBuffer")
      .def_ro("width", &brdfcl::GBuffer::width)
      .def_ro("height", &brdfcl::GBuffer::height);
  m.def("read_gbuffer", [](const std::string& path, bool check) {
    brdfcl::GBufferReadOptions o;
    o.check = check;
    nb::gil_scoped_release release;
    return brdfcl::readGBuffer(path, o);
  }, "path"_a, "check"_a);
  m.def("gbuffer_from_dict", &gbufferFromDict, "channels"_a);
  m.def("check_gbuffer", [](const brdfcl::GBuffer& g, const std::string& shown) {
    nb::gil_scoped_release release;
    brdfcl::checkGBufferValues(g, shown, "check=False");
  }, "gbuffer"_a, "shown"_a);
  m.def("shade_camera_warning", &brdfcl::shadeCameraWarning, "scene_name"_a, "scene"_a, "gbuffer_name"_a, "gbuffer"_a);
  m.def("gbuffer_to_dict", [](brdfcl::GBuffer g) { return gbufferToDict(std::move(g)); }, "gbuffer"_a);
  m.def("write_gbuffer", [](const std::string& path, const brdfcl::GBuffer& g, bool half) {
    nb::gil_scoped_release release;
    brdfcl::writeGBuffer(path, g, half);
  }, "path"_a, "gbuffer"_a, "half"_a);
}

}  // namespace brdfcl_python
