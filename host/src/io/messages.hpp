// Helpers that keep the readers' error messages on one line and quote what the user wrote,
// shared by every reader of user files (materials, samples, scene, G-buffer, images).
#pragma once
#include <cstddef>
#include <string>
#include <string_view>
#include <vector>

#include <nlohmann/json_fwd.hpp>

namespace brdfcl::detail {

// `s` cut at maxLength (then "...") with control characters replaced, so a message stays one line.
std::string printable(std::string_view s, std::size_t maxLength = 60, char replacement = '?');

// A number as a user would write it: whole numbers without exponent (12, 10000000000), "nan", "inf".
std::string formatNumber(double d);

// What a JSON value is, for "got ..." in messages: a number, string "x", true, null, an array of 3 elements.
std::string describeJson(const nlohmann::json& v);

// A writer's failure text (OpenEXR names the file it was writing) with the temporary file beside
// the output replaced by the output's own path: the temporary no longer exists when the user reads it.
std::string withUserPath(std::string what, const std::string& tmpPath, const std::string& userPath);

// nlohmann's parse error without its "[json.exception.parse_error.101] " tag.
std::string withoutJsonTag(std::string what);

// For "did you mean ...": the candidate nearest to `word` by Damerau (optimal string alignment)
// distance, ignoring ASCII case, when that distance is at most a third of the length of what
// follows their common start (at least 1), or when one is the other cut short to no less than
// half; "" when none is that near, so that far names get no far-fetched suggestions.
std::string closestName(std::string_view word, const std::vector<std::string_view>& candidates);

}  // namespace brdfcl::detail
