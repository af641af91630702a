// brdfcl._core's images: EXR reading, `brdfcl render`'s tone mapping to 8-bit sRGB, and
// `brdfcl diff`'s numbers of two EXR files or two arrays.
#include <nanobind/stl/string.h>
#include <nanobind/stl/tuple.h>

#include <cstdint>
#include <string>
#include <tuple>
#include <vector>

#include "bindings.hpp"
#include "brdfcl/error.hpp"
#include "brdfcl/image.hpp"
#include "host/src/parity/diff.hpp"

using namespace nanobind::literals;

namespace brdfcl_python {

using brdfcl::Error;

void bindImages(nb::module_& m) {
  m.def("read_exr", [](const std::string& path) {
    brdfcl::Image img;
    {
      nb::gil_scoped_release release;
      img.rgb = brdfcl::readExrRgb(path, img.width, img.height);
    }
    return imageToNumpy(std::move(img));
  }, "path"_a);

  // `brdfcl render`'s PNG pixels (exposure, PBR Neutral, sRGB, 8 bits) of a C-contiguous float32 (H, W, 3) array.
  m.def("tone_map", [](const nb::ndarray<const float, nb::ndim<3>, nb::c_contig, nb::device::cpu>& rgb, float exposure) {
    if (rgb.shape(2) != 3) throw Error("the image must have shape (H, W, 3), got " + std::to_string(rgb.shape(2)) + " channels");
    const std::size_t h = rgb.shape(0), w = rgb.shape(1);
    std::vector<std::uint8_t> bytes;
    {
      nb::gil_scoped_release release;
      bytes = brdfcl::displayRgb8(rgb.data(), h * w, exposure);
    }
    auto* held = new std::vector<std::uint8_t>(std::move(bytes));
    nb::capsule owner(held, [](void* p) noexcept { delete static_cast<std::vector<std::uint8_t>*>(p); });
    return nb::ndarray<nb::numpy, std::uint8_t>(held->data(), {h, w, 3}, owner);
  }, "rgb"_a, "exposure"_a);
  // `brdfcl diff`'s numbers: d per pixel (H, W), the report as JSON text, and the default colour
  // range; of two EXR files (the CLI's reader and checks) or two arrays of one shape.
  const auto diffResult = [](brdfcl::ImageDiff&& d, const std::string& nameA, const std::string& nameB) {
    const double range = brdfcl::defaultDiffRange(d.stats);
    const std::string json = brdfcl::imageDiffJson(d.stats, nameA, nameB, range, "");
    const auto h = std::size_t(d.stats.height), w = std::size_t(d.stats.width);
    return std::make_tuple(toNumpy(std::move(d.relative), {h, w}), json, range);
  };
  m.def("image_diff_files", [diffResult](const std::string& a, const std::string& b, double threshold, double floor) {
    brdfcl::ImageDiffOptions o;
    o.threshold = threshold;
    o.floor = floor;
    brdfcl::ImageDiff d;
    {
      nb::gil_scoped_release release;
      d = brdfcl::diffExrFiles(a, b, o);
    }
    return diffResult(std::move(d), a, b);
  }, "a"_a, "b"_a, "threshold"_a, "floor"_a);
  m.def("image_diff_arrays", [diffResult](const nb::ndarray<const float, nb::ndim<3>, nb::c_contig, nb::device::cpu>& a,
                                          const nb::ndarray<const float, nb::ndim<3>, nb::c_contig, nb::device::cpu>& b,
                                          double threshold, double floor, const std::string& nameA, const std::string& nameB) {
    if (a.shape(2) != 3 || b.shape(2) != 3 || a.shape(0) != b.shape(0) || a.shape(1) != b.shape(1))
      throw Error("internal: image_diff_arrays takes two (H, W, 3) arrays of one shape", 3);
    const int h = int(a.shape(0)), w = int(a.shape(1));
    brdfcl::ImageDiffOptions o;
    o.threshold = threshold;
    o.floor = floor;
    brdfcl::ImageDiff d;
    {
      nb::gil_scoped_release release;
      d = brdfcl::diffImages(std::vector<float>(a.data(), a.data() + a.size()),
                             std::vector<float>(b.data(), b.data() + b.size()), w, h, o);
    }
    return diffResult(std::move(d), nameA, nameB);
  }, "a"_a, "b"_a, "threshold"_a, "floor"_a, "name_a"_a, "name_b"_a);
}

}  // namespace brdfcl_python
