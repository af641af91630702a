// What the binding files of brdfcl._core share: the array types, the Materials and Device
// objects that Python holds between calls, and one bind function per area (each in its own
// file), called in order by NB_MODULE in module.cpp.
#pragma once

#include <nanobind/nanobind.h>
#include <nanobind/ndarray.h>
#include <nanobind/stl/string.h>

#include <cstddef>
#include <initializer_list>
#include <map>
#include <memory>
#include <mutex>
#include <string>
#include <tuple>
#include <utility>
#include <vector>

#include "brdfcl/evaluator.hpp"
#include "brdfcl/material.hpp"
#include "brdfcl/render.hpp"
#include "brdfcl/runtime.hpp"

namespace brdfcl_python {

namespace nb = nanobind;

using InArray = nb::ndarray<nb::ro, nb::c_contig, nb::device::cpu>;
using OutArray = nb::ndarray<float, nb::c_contig, nb::device::cpu>;

// A float32 numpy array that owns `values` (moved, never copied).
inline nb::ndarray<nb::numpy, float> toNumpy(std::vector<float>&& values, std::initializer_list<std::size_t> shape) {
  auto* held = new std::vector<float>(std::move(values));
  nb::capsule owner(held, [](void* p) noexcept { delete static_cast<std::vector<float>*>(p); });
  return nb::ndarray<nb::numpy, float>(held->data(), shape, owner);
}

inline nb::ndarray<nb::numpy, float> imageToNumpy(brdfcl::Image&& img) {
  const auto h = std::size_t(img.height), w = std::size_t(img.width);
  return toNumpy(std::move(img.rgb), {h, w, 3});
}

// A device as brdfcl.devices() and Device.info show it.
inline nb::dict deviceDict(const brdfcl::DeviceInfo& i) {
  nb::dict d;
  d["index"] = i.index;
  d["name"] = i.name;
  d["platform"] = i.platform;
  d["type"] = i.type;
  d["compute_units"] = i.computeUnits;
  d["opencl_c"] = i.openclC;
  d["max_alloc"] = i.maxAlloc;
  d["global_mem"] = i.globalMem;
  return d;
}

// Materials parsed once on the Python side and passed to every call that evaluates them.
struct Materials {
  std::vector<brdfcl::MaterialParams> list;
  std::vector<std::string> warnings;
};

// One device and the evaluators of every option set used on it, made on first use. Evaluators
// are thread-safe (evaluator.hpp), so one per option set serves every thread.
class Device {
 public:
  explicit Device(const std::string& selector) : rt_(selector) {}

  brdfcl::Runtime& runtime() { return rt_; }

  brdfcl::Evaluator& evaluator(const brdfcl::EvalOptions& o) {
    const auto key = std::make_tuple(int(o.sheenVisibility), int(o.sheenDistribution), int(o.sheenScaling), int(o.lobe),
                                     int(o.profile));
    std::lock_guard<std::mutex> lock(mutex_);
    auto& slot = evaluators_[key];
    if (!slot) slot = std::make_unique<brdfcl::Evaluator>(rt_, o);
    return *slot;
  }

  nb::dict info() const { return deviceDict(rt_.info()); }

 private:
  brdfcl::Runtime rt_;
  std::mutex mutex_;
  std::map<std::tuple<int, int, int, int, int>, std::unique_ptr<brdfcl::Evaluator>> evaluators_;
};

void bindErrors(nb::module_& m);                           // errors.cpp
void bindOptions(nb::module_& m);                          // options.cpp: devices, materials, EvalOptions
void bindEval(nb::class_<Device>& device);                 // eval.cpp: evaluate, albedo, lut
void bindRender(nb::module_& m, nb::class_<Device>& device);  // render.cpp: render, shade, RenderJob
void bindGbuffer(nb::module_& m);                          // gbuffer.cpp
void bindImages(nb::module_& m);                           // images.cpp: EXR, tone map, image diff
void bindScene(nb::module_& m);                            // render.cpp
void bindDeviceArrays(nb::module_& m);                     // device_array.cpp
void bindSample(nb::module_& m);                           // sample.cpp: sample, pdf, uniforms

}  // namespace brdfcl_python
