// Command-line checks ahead of CLI11's parse. CLI11 2.1 reports a missing required option before
// an unknown one, and "A subcommand is required" for a misspelt subcommand; users need the typo.
#include "arguments.hpp"

#include <cctype>
#include <string_view>

#include <fmt/format.h>

#include "brdfcl/error.hpp"
#include "host/src/io/messages.hpp"

namespace brdfcl::cli {

namespace {
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
  const std::vector<std::string_view> views(candidates.begin(), candidates.end());
  return detail::closestName(word, views);
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
