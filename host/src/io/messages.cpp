// One-line message helpers for the readers of user files (see messages.hpp).
#include "io/messages.hpp"

#include "brdfcl/error.hpp"

#include <algorithm>
#include <cctype>
#include <charconv>
#include <cmath>

#include <nlohmann/json.hpp>

namespace brdfcl {
namespace {
// Length of the valid UTF-8 sequence starting at s[i] (RFC 3629: no overlong forms, no
// surrogates, nothing above U+10FFFF), or 0 when the bytes there are not one.
std::size_t utf8Length(const std::string& s, std::size_t i) {
  const auto byte = [&](std::size_t k) { return static_cast<unsigned char>(s[k]); };
  const unsigned char c = byte(i);
  if (c < 0x80) return 1;
  std::size_t n;
  unsigned char lo = 0x80, hi = 0xBF;
  if (c >= 0xC2 && c <= 0xDF) {
    n = 2;
  } else if (c >= 0xE0 && c <= 0xEF) {
    n = 3;
    if (c == 0xE0) lo = 0xA0;
    if (c == 0xED) hi = 0x9F;
  } else if (c >= 0xF0 && c <= 0xF4) {
    n = 4;
    if (c == 0xF0) lo = 0x90;
    if (c == 0xF4) hi = 0x8F;
  } else {
    return 0;
  }
  if (i + n > s.size()) return 0;
  if (byte(i + 1) < lo || byte(i + 1) > hi) return 0;
  for (std::size_t k = 2; k < n; ++k)
    if (byte(i + k) < 0x80 || byte(i + k) > 0xBF) return 0;
  return n;
}
}  // namespace

const char* toString(ErrorKind kind) {
  switch (kind) {
    case ErrorKind::Input: return "input";
    case ErrorKind::Environment: return "environment";
    case ErrorKind::Device: return "device";
    case ErrorKind::Memory: return "memory";
    case ErrorKind::Internal: return "internal";
  }
  return "internal";
}

std::string escapeMessage(const std::string& s) {
  static const char* hex = "0123456789ABCDEF";
  std::string out;
  out.reserve(s.size());
  for (std::size_t i = 0; i < s.size();) {
    const auto c = static_cast<unsigned char>(s[i]);
    const std::size_t n = utf8Length(s, i);
    if (n == 0 || (c < 0x20 && c != '\n' && c != '\t') || c == 0x7f) {
      out += "\\x";
      out += hex[c >> 4];
      out += hex[c & 15];
      ++i;
    } else {
      out.append(s, i, n);
      i += n;
    }
  }
  return out;
}
}  // namespace brdfcl

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

namespace {
std::size_t osaDistance(std::string_view a, std::string_view b) {
  const auto lower = [](char c) { return static_cast<char>(std::tolower(static_cast<unsigned char>(c))); };
  const std::size_t n = a.size(), m = b.size();
  std::vector<std::size_t> d((n + 1) * (m + 1));
  const auto at = [&](std::size_t i, std::size_t j) -> std::size_t& { return d[i * (m + 1) + j]; };
  for (std::size_t i = 0; i <= n; ++i) at(i, 0) = i;
  for (std::size_t j = 0; j <= m; ++j) at(0, j) = j;
  for (std::size_t i = 1; i <= n; ++i)
    for (std::size_t j = 1; j <= m; ++j) {
      const std::size_t cost = lower(a[i - 1]) == lower(b[j - 1]) ? 0 : 1;
      at(i, j) = std::min({at(i - 1, j) + 1, at(i, j - 1) + 1, at(i - 1, j - 1) + cost});
      if (i > 1 && j > 1 && lower(a[i - 1]) == lower(b[j - 2]) && lower(a[i - 2]) == lower(b[j - 1]))
        at(i, j) = std::min(at(i, j), at(i - 2, j - 2) + 1);
    }
  return at(n, m);
}
}  // namespace

std::string closestName(std::string_view word, const std::vector<std::string_view>& candidates) {
  if (word.size() > 200) return {};  // hostile keys: the table is quadratic
  const auto lower = [](char c) { return std::tolower(static_cast<unsigned char>(c)); };
  std::string_view best;
  std::size_t bestDistance = 0;
  for (const std::string_view c : candidates) {
    // The allowance scales with what differs after the shared start, so that a long common
    // prefix (KHR_materials_) does not make far names "near".
    std::size_t common = 0;
    while (common < word.size() && common < c.size() && lower(word[common]) == lower(c[common])) ++common;
    const std::size_t dist = osaDistance(word, c);
    // A dropped suffix ("clearcoatRoughness" for clearcoatRoughnessFactor) is a typo too.
    const bool truncated = common == std::min(word.size(), c.size()) && 2 * common >= std::max(word.size(), c.size());
    if (!truncated && dist > std::max<std::size_t>(1, (c.size() - common) / 3)) continue;
    if (best.empty() || dist < bestDistance) {
      best = c;
      bestDistance = dist;
    }
  }
  return std::string(best);
}

}  // namespace brdfcl::detail
