// Checks of the command line that CLI11 does too late or too vaguely: an unknown subcommand or
// option is named first (before any missing required option), with "did you mean".
#pragma once
#include <string>
#include <vector>

#include <CLI/CLI.hpp>

namespace brdfcl::cli {

// The closest of `candidates` to `word` (detail::closestName: a small edit distance, any case), or "".
std::string closestMatch(const std::string& word, const std::vector<std::string>& candidates);

// Throws brdfcl::Error naming the first unknown subcommand or option in argv[1..argc), with a
// suggestion and the help to read. Returns the subcommand named (or "" when there is none).
std::string checkArguments(CLI::App& app, int argc, char** argv);

}  // namespace brdfcl::cli
