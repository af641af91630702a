// brdfcl._core's exception classes: brdfcl.Error and one subclass per brdfcl::ErrorKind, and the
// translator that raises them from brdfcl::Error and std::bad_alloc.
#include <exception>
#include <iterator>
#include <new>
#include <string>

#include "bindings.hpp"
#include "brdfcl/error.hpp"

namespace brdfcl_python {

void bindErrors(nb::module_& m) {
  // brdfcl.Error is the base of one class per brdfcl::ErrorKind, each also deriving the built-in
  // class a Python caller expects of that kind, so `except brdfcl.Error` and `except ValueError`
  // (or OSError, RuntimeError, MemoryError) both catch it.
  static PyObject* errorBase = PyErr_NewExceptionWithDoc(
      "brdfcl._core.Error", "Every error brdfcl raises; its .kind says who can fix it.", PyExc_Exception, nullptr);
  struct KindClass {
    brdfcl::ErrorKind kind;
    const char* name;
    PyObject* builtin;
    const char* doc;
  };
  static const KindClass kinds[] = {
      {brdfcl::ErrorKind::Input, "InputError", PyExc_ValueError, "A bad argument, file or value (a ValueError)."},
      {brdfcl::ErrorKind::Environment, "EnvironmentError", PyExc_OSError,
       "No OpenCL platform or device, or an unusable cache folder (an OSError)."},
      {brdfcl::ErrorKind::Device, "DeviceError", PyExc_RuntimeError,
       "An OpenCL call or kernel build failed on the device (a RuntimeError)."},
      {brdfcl::ErrorKind::Memory, "OutOfMemoryError", PyExc_MemoryError, "Host or device memory ran out (a MemoryError)."},
      {brdfcl::ErrorKind::Internal, "InternalError", PyExc_RuntimeError, "A fault in brdfcl itself (a RuntimeError)."},
  };
  static PyObject* kindClass[std::size(kinds)];
  PyObject_SetAttrString(errorBase, "kind", nb::str("").ptr());
  m.attr("Error") = nb::handle(errorBase);
  for (std::size_t i = 0; i < std::size(kinds); ++i) {
    const nb::object bases = nb::make_tuple(nb::handle(errorBase), nb::handle(kinds[i].builtin));
    kindClass[i] = PyErr_NewExceptionWithDoc((std::string("brdfcl._core.") + kinds[i].name).c_str(), kinds[i].doc,
                                             bases.ptr(), nullptr);
    if (kindClass[i] == nullptr) throw nb::python_error();
    PyObject_SetAttrString(kindClass[i], "kind", nb::str(brdfcl::toString(kinds[i].kind)).ptr());
    m.attr(kinds[i].name) = nb::handle(kindClass[i]);
  }
  nb::register_exception_translator([](const std::exception_ptr& p, void*) {
    try {
      std::rethrow_exception(p);
    } catch (const brdfcl::Error& e) {
      for (std::size_t i = 0; i < std::size(kinds); ++i)
        if (kinds[i].kind == e.kind()) PyErr_SetString(kindClass[i], e.what());
    } catch (const std::bad_alloc&) {
      PyErr_SetString(kindClass[3] /* Memory */, brdfcl::outOfMemoryMessage().c_str());
    }
  });
}

}  // namespace brdfcl_python
