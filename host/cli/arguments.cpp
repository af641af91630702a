// Command-line checks ahead of CLI11's parse. CLI11 2.1 reports a missing required option before
// an unknown one, and "A subcommand is required" for a misspelt subcommand; users need the typo.
#include "arguments.hpp"

#include <algorithm>
#include <cctype>

#include <fmt/format.h>

#include "brdfcl/error.hpp"

namespace brdfcl::cli {

namespace {
// Optimal string alignment distance (Damerau-Levenshtein with adjacent transpositions): one
// swapped pair of letters, the most common typo, costs 1.
std::size_t editDistance(const std::string& a, const std::string& b) {
  const std::size_t n = a.size(), m = b.size();
  std::vector<std::vector<std::size_t>> d(n + 1, std::vector<std::size_t>(m + 1));
  for (std::size_t i = 0; i <= n; ++i) d[i][0] = i;
  for (std::size_t j = 0; j <= m; ++j) d[0][j] = j;
  for (std::size_t i = 1; i <= n; ++i)
    for (std::size_t j = 1; j <= m; ++j) {
      const std::size_t cost = a[i - 1] == b[j - 1] ? 0 : 1;
      d[i][j] = std::min({d[i - 1][j] + 1, d[i][j - 1] + 1, d[i - 1][j - 1] + cost});
      if (i > 1 && j > 1 && a[i - 1] == b[j - 2] && a[i - 2] == b[j - 1]) d[i][j] = std::min(d[i][j], d[i - 2][j - 2] + 1);
    }
  return d[n][m];
}

std::string lower(std::string s) {
  for (auto& c : s) c = char(std::tolower(static_cast<unsigned char>(c)));
  return s;
}

std::vector<std::string> subcommandNames(CLI::App& app) {
  std::vector<std::string> names;
  for (const CLI::App* sub : app.get_subcommands([](CLI::App*) { return true; })) names.push_back(sub->get_name());
  return names;
}

std::vector<std::string> longOptionNames(const CLI::App& cmd) {
  std::vector<std::string> names;
  for (const CLI::Option* o : cmd.get_options())
    for (const auto& l : o->get_lnames()) names.push_back("--" + l);
  return names;
}

std::string suggestion(const std::string& match) { return match.empty() ? "" : fmt::format(" (did you mean '{}'?)", match); }

bool isOptionToken(const std::string& t) {
  // "-" is stdin/stdout and "-0.5" a negative value, not options.
  return t.size() >= 2 && t[0] == '-' && !std::isdigit(static_cast<unsigned char>(t[1])) && t[1] != '.';
}
}  // namespace

std::string closestMatch(const std::string& word, const std::vector<std::string>& candidates) {
  const std::string w = lower(word);
  // A third of the word's length, at least one and at most three edits: "evl" finds eval,
  // "frobnicate" finds nothing.
  const std::size_t limit = std::clamp<std::size_t>(w.size() / 3, 1, 3);
  std::string best;
  std::size_t bestDistance = limit + 1;
  for (const auto& c : candidates) {
    const std::size_t d = editDistance(w, lower(c));
    if (d < bestDistance) {
      bestDistance = d;
      best = c;
    }
  }
  return best;
}

std::string checkArguments(CLI::App& app, int argc, char** argv) {
  if (argc < 2) return "";
  const std::string first = argv[1];
  if (isOptionToken(first)) {
    if (first == "-h" || first == "--help" || first == "--help-all" || first == "--version") return "";
    const auto names = subcommandNames(app);
    throw Error(fmt::format("unknown option '{}'{}; brdfcl takes a subcommand first ({}); see 'brdfcl --help'", first,
                            suggestion(closestMatch(first, {"--help", "--version"})), fmt::join(names, ", ")));
  }
  CLI::App* cmd = nullptr;
  for (CLI::App* sub : app.get_subcommands([](CLI::App*) { return true; }))
    if (sub->get_name() == first) cmd = sub;
  if (!cmd) {
    const std::string match = first == "version" || first == "help" ? "brdfcl --" + first
                                                                     : closestMatch(first, subcommandNames(app));
    throw Error(fmt::format("unknown subcommand '{}'{}; see 'brdfcl --help'", first, suggestion(match)));
  }
  const auto known = longOptionNames(*cmd);
  for (int i = 2; i < argc; ++i) {
    const std::string token = argv[i];
    if (token == "--") break;
    if (!isOptionToken(token)) continue;
    const std::string name = token.substr(0, token.find('='));
    if (name == "-h" || name == "--help") continue;
    if (cmd->get_option_no_throw(name) != nullptr) {
      // Skip the option's value, so that a value that looks like an option ("--out -x.csv") is not judged.
      const CLI::Option* o = cmd->get_option_no_throw(name);
      if (token.find('=') == std::string::npos && o->get_type_size() != 0 && i + 1 < argc) ++i;
      continue;
    }
    throw Error(fmt::format("{}: unknown option '{}'{}; see 'brdfcl {} --help'", cmd->get_name(), name,
                            suggestion(closestMatch(name, known)), cmd->get_name()));
  }
  return cmd->get_name();
}

}  // namespace brdfcl::cli
