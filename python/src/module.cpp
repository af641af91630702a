// brdfcl._core: the nanobind bindings of the C++ host library (brdfcl_core) that the pure-Python
// front (python/brdfcl/__init__.py) calls. No BRDF maths here: every call goes to the same library
// functions the CLI uses, with the GIL released while the device works. One file per area binds it.
#include <nanobind/nanobind.h>

#include "bindings.hpp"
#include "host/src/io/option_style.hpp"

namespace nb = nanobind;

NB_MODULE(_core, m) {
  m.doc() = "brdfcl's C++ host library (brdfcl_core); use the brdfcl package, not this module.";
  // Every message names options as this process's callers write them: lobe=, not --lobe.
  brdfcl::setOptionStyle(brdfcl::OptionStyle::Python);
  brdfcl_python::bindErrors(m);
  brdfcl_python::bindOptions(m);
  nb::class_<brdfcl_python::Device> device(m, "Device");
  brdfcl_python::bindEval(device);
  brdfcl_python::bindRender(m, device);
  brdfcl_python::bindGbuffer(m);
  brdfcl_python::bindImages(m);
  brdfcl_python::bindScene(m);
  brdfcl_python::bindSample(m);
  brdfcl_python::bindDeviceArrays(m);
}
