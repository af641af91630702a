// How messages name an option: in the CLI's spelling (--ibl-samples) or as a Python keyword
// (ibl_samples=), so that one validation in the library serves both callers.
#pragma once
#include <string>

namespace brdfcl {

// How a message names an option: as the CLI spells it ("--ibl-samples 0") or as the Python keyword
// ("ibl_samples=0"). One validation serves both callers; only the words differ. The style is the
// process's: Cli unless set, Python once the Python module is imported (every call in that
// process comes through it, worker threads included).
enum class OptionStyle { Cli, Python };
OptionStyle optionStyle();
void setOptionStyle(OptionStyle style);

// `cliOption` ("--sheen-visibility") as the style names it: unchanged, or the keyword with its
// "=" ("sheen_visibility=").
std::string optionName(const std::string& cliOption);
// A flag that is given to turn something on: "--allow-outside-uris" or "allow_outside_uris=True".
std::string flagName(const std::string& cliFlag);
// An option with its value, `value` written as the CLI shows it: "--spp 0" or "spp=0", "--ibl 'x'"
// or "ibl='x'"; anything but an option (a file name) keeps the space. pythonQuotes: a string the
// CLI shows bare ("--profile threejs") that Python shows as a str literal ("profile='threejs'").
std::string optionWithValue(const std::string& cliOption, const std::string& value, bool pythonQuotes = false);

}  // namespace brdfcl
