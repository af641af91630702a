// One-line message helpers for the readers of user files (see messages.hpp).
#include "io/messages.hpp"

#include <charconv>
#include <cmath>

#include <nlohmann/json.hpp>

namespace brdfcl::detail {

std::string printable(std::string_view s, std::size_t maxLength, char replacement) {
  std::string out;
  for (char c : s) {
    if (out.size() >= maxLength) {
      out += "...";
      break;
    }
    out += (static_cast<unsigned char>(c) < 0x20 || c == 0x7f) ? replacement : c;
  }
  return out;
}

std::string formatNumber(double d) {
  if (std::isnan(d)) return "nan";
  if (std::isinf(d)) return d > 0 ? "inf" : "-inf";
  char buf[64];
  const bool whole = std::floor(d) == d && std::fabs(d) < 1e17;
  const auto r = whole ? std::to_chars(buf, buf + sizeof buf, d, std::chars_format::fixed)
                       : std::to_chars(buf, buf + sizeof buf, d);
  return std::string(buf, r.ptr);
}

std::string describeJson(const nlohmann::json& v) {
  using json = nlohmann::json;
  switch (v.type()) {
    case json::value_t::number_float:
    case json::value_t::number_integer:
    case json::value_t::number_unsigned:
      return formatNumber(v.get<double>());
    case json::value_t::string:
      return "string \"" + printable(v.get_ref<const std::string&>()) + "\"";
    case json::value_t::boolean:
      return v.get<bool>() ? "true" : "false";
    case json::value_t::null:
      return "null";
    case json::value_t::array:
      return "an array of " + std::to_string(v.size()) + (v.size() == 1 ? " element" : " elements");
    case json::value_t::object:
      return "an object";
    default:
      return "an unsupported value";
  }
}

std::string withUserPath(std::string what, const std::string& tmpPath, const std::string& userPath) {
  if (tmpPath.empty()) return what;
  for (auto at = what.find(tmpPath); at != std::string::npos; at = what.find(tmpPath, at + userPath.size()))
    what.replace(at, tmpPath.size(), userPath);
  return what;
}

std::string withoutJsonTag(std::string what) {
  const auto tag = what.find("] ");
  if (what.rfind("[json.exception", 0) == 0 && tag != std::string::npos) what.erase(0, tag + 2);
  return what;
}

}  // namespace brdfcl::detail
