// brdfcl._core's DeviceArray: float32 or uint32 arrays in a device's memory (brdfcl/device_array.hpp),
// so chained evaluations stay on the device. The Python front keeps their shape and dtype.
#include <cstddef>

#include "bindings.hpp"
#include "brdfcl/device_array.hpp"
#include "brdfcl/error.hpp"

using namespace nanobind::literals;

namespace brdfcl_python {

using brdfcl::Error;

void bindDeviceArrays(nb::module_& m) {
  // The array keeps its Device alive.
  nb::class_<brdfcl::DeviceArray>(m, "DeviceArray")
      .def("__init__",
           [](brdfcl::DeviceArray* self, Device& d, bool uint32, std::size_t size) {
             new (self) brdfcl::DeviceArray(d.runtime(), uint32 ? brdfcl::DeviceArray::Type::UInt32
                                                                : brdfcl::DeviceArray::Type::Float32, size);
           },
           "device"_a, "uint32"_a, "size"_a, nb::keep_alive<1, 2>())
      .def_prop_ro("size", &brdfcl::DeviceArray::size)
      .def("upload",
           [](brdfcl::DeviceArray& a, InArray host) {
             if (host.itemsize() != 4) throw Error("internal: device arrays hold 4-byte elements", 3);
             const std::size_t n = host.size();
             const void* p = host.data();
             nb::gil_scoped_release release;
             a.upload(p, n);
           },
           "host"_a.noconvert())
      .def("download",
           [](const brdfcl::DeviceArray& a, nb::ndarray<nb::c_contig, nb::device::cpu> host) {
             if (host.itemsize() != 4 || host.size() != a.size()) throw Error("internal: download into the wrong array", 3);
             void* p = host.data();
             nb::gil_scoped_release release;
             a.download(p, a.size());
           },
           "host"_a.noconvert());
}

}  // namespace brdfcl_python
