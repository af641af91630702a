// brdfcl._core's renders: Device.render (the CLI's renderJob: glTF or spheres, frames, lights and
// environment), Device.shade of a G-buffer, the RenderJob fields, and scenes.
#include <nanobind/stl/pair.h>
#include <nanobind/stl/string.h>
#include <nanobind/stl/vector.h>

#include <string>
#include <utility>
#include <vector>

#include "bindings.hpp"
#include "brdfcl/error.hpp"
#include "brdfcl/gbuffer.hpp"
#include "brdfcl/render.hpp"
#include "brdfcl/render_job.hpp"
#include "brdfcl/scene.hpp"
#include "host/src/model/pack.hpp"

using namespace nanobind::literals;

namespace brdfcl_python {

void bindRender(nb::module_& m, nb::class_<Device>& device) {
  device
      .def("render",
           [](Device& d, brdfcl::RenderJob job, const std::string& ibl, int iblSamples, bool iblSamplesGiven) {
             job.shade.ibl = brdfcl::parseIblMode(ibl);
             brdfcl::checkIblSamples(iblSamples);
             brdfcl::checkIblSamplesApply(job.shade.ibl, iblSamplesGiven);
             job.shade.iblSamples = iblSamples;
             std::vector<std::string> warnings;
             job.warn = [&warnings](const std::string& w) { warnings.push_back(w); };
             brdfcl::Image img;
             {
               nb::gil_scoped_release release;
               img = brdfcl::renderJob(d.runtime(), job);
             }
             return std::make_pair(imageToNumpy(std::move(img)), warnings);
           },
           "job"_a, "ibl"_a, "ibl_samples"_a, "ibl_samples_given"_a)
      .def("shade",
           [](Device& d, const brdfcl::GBuffer& g, const brdfcl::Scene& scene, const std::string& profile,
              const std::string& ibl, int iblSamples) {
             brdfcl::EvalOptions o;
             o.profile = brdfcl::parseProfile(profile);
             brdfcl::ShadeOptions so;
             so.ibl = brdfcl::parseIblMode(ibl);
             brdfcl::checkIblSamples(iblSamples);
             so.iblSamples = iblSamples;
             brdfcl::Image img;
             {
               nb::gil_scoped_release release;
               brdfcl::Shader shader(d.runtime(), scene, o);
               img = shader.shade(g, so);
             }
             return imageToNumpy(std::move(img));
           },
           "gbuffer"_a, "scene"_a, "profile"_a, "ibl"_a, "ibl_samples"_a);

  nb::class_<brdfcl::RenderJob>(m, "RenderJob")
      .def(nb::init<>())
      .def_rw("gltf", &brdfcl::RenderJob::gltf)
      .def_rw("scene", &brdfcl::RenderJob::scene)
      .def_rw("width", &brdfcl::RenderJob::width)
      .def_rw("height", &brdfcl::RenderJob::height)
      .def_rw("camera", &brdfcl::RenderJob::camera)
      .def_rw("gltf_scene", &brdfcl::RenderJob::gltfScene)
      .def_rw("variant", &brdfcl::RenderJob::variant)
      .def_rw("strict", &brdfcl::RenderJob::strict)
      .def_rw("allow_outside_uris", &brdfcl::RenderJob::allowOutsideUris)
      .def_rw("spp", &brdfcl::RenderJob::spp)
      .def_rw("spp_given", &brdfcl::RenderJob::sppGiven)
      .def_rw("environment", &brdfcl::RenderJob::environment)
      .def_rw("env_intensity", &brdfcl::RenderJob::envIntensity)
      .def_rw("env_rotation", &brdfcl::RenderJob::envRotation)
      .def_rw("environment_given", &brdfcl::RenderJob::environmentGiven)
      .def_rw("lights", &brdfcl::RenderJob::lights)
      .def("set_profile", [](brdfcl::RenderJob& j, const std::string& p) { j.model.profile = brdfcl::parseProfile(p); });
}

void bindScene(nb::module_& m) {
  nb::class_<brdfcl::Scene>(m, "Scene");
  m.def("read_scene", &brdfcl::readScene, "path"_a, "allow_outside"_a = false);
  m.def("parse_scene", &brdfcl::parseScene, "json"_a, "name"_a, "base_dir"_a, "allow_outside"_a = false);
  m.def("spheres_scene", &brdfcl::spheresScene);
}

}  // namespace brdfcl_python
