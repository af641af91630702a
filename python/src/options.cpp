// brdfcl._core's devices list, materials (read once, passed to every call) and evaluation options
// (parsed and checked by the library's own option spellings).
#include <nanobind/stl/string.h>
#include <nanobind/stl/vector.h>

#include <string>
#include <vector>

#include "bindings.hpp"
#include "brdfcl/error.hpp"
#include "brdfcl/io.hpp"
#include "host/src/io/option_style.hpp"
#include "host/src/model/pack.hpp"

using namespace nanobind::literals;

namespace brdfcl_python {
namespace {

Materials readMaterials(const std::string& path, bool strict) {
  Materials m;
  brdfcl::MaterialReadOptions o;
  o.strict = strict;
  o.warn = [&m](const std::string& w) { m.warnings.push_back(w); };
  m.list = brdfcl::readMaterials(path, o);
  return m;
}

Materials parseMaterials(const std::string& json, const std::string& name, bool strict) {
  Materials m;
  brdfcl::MaterialReadOptions o;
  o.strict = strict;
  o.warn = [&m](const std::string& w) { m.warnings.push_back(w); };
  m.list = brdfcl::parseMaterials(json, name, o);
  return m;
}

brdfcl::EvalOptions evalOptions(const std::string& lobe, const std::string& visibility, const std::string& distribution,
                                const std::string& scaling, const std::string& profile) {
  brdfcl::EvalOptions o;
  o.profile = brdfcl::parseProfile(profile);
  o.sheenVisibility = brdfcl::parseSheenVisibility(visibility);
  o.sheenDistribution = brdfcl::parseSheenDistribution(distribution);
  o.sheenScaling = brdfcl::parseSheenScaling(scaling);
  o.lobe = brdfcl::parseLobe(lobe);
  brdfcl::checkProfileOptions(o);
  return o;
}

}  // namespace

void bindOptions(nb::module_& m) {
  // `python -m brdfcl` is a command line: its messages name its --options, as the CLI's do.
  m.def("set_cli_option_style", [] { brdfcl::setOptionStyle(brdfcl::OptionStyle::Cli); });

  m.def("devices", [] {
    std::vector<nb::dict> out;
    for (const auto& i : brdfcl::listDevices()) out.push_back(deviceDict(i));
    return out;
  });

  nb::class_<Materials>(m, "Materials")
      .def("__len__", [](const Materials& x) { return x.list.size(); })
      .def_prop_ro("warnings", [](const Materials& x) { return x.warnings; })
      .def_prop_ro("names", [](const Materials& x) {
        std::vector<std::string> n;
        for (const auto& p : x.list) n.push_back(p.name);
        return n;
      });
  m.def("read_materials", &readMaterials, "path"_a, "strict"_a);
  m.def("parse_materials", &parseMaterials, "json"_a, "name"_a, "strict"_a);
  m.def("select_material", [](const Materials& x, std::size_t i) {
    if (i >= x.list.size()) throw brdfcl::Error("internal: material index out of range", 3);
    Materials one;
    one.list = {x.list[i]};
    return one;
  });

  nb::class_<brdfcl::EvalOptions>(m, "EvalOptions");
  m.def("eval_options", &evalOptions, "lobe"_a, "sheen_visibility"_a, "sheen_distribution"_a, "sheen_scaling"_a,
        "profile"_a);
}

}  // namespace brdfcl_python
