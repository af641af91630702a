// The process's option style (option_style.hpp): how library messages name an option.
#include "io/option_style.hpp"

#include <atomic>

namespace brdfcl {

namespace {
std::atomic<OptionStyle> gStyle{OptionStyle::Cli};
}

OptionStyle optionStyle() { return gStyle.load(std::memory_order_relaxed); }
void setOptionStyle(OptionStyle style) { gStyle.store(style, std::memory_order_relaxed); }

std::string optionName(const std::string& cliOption) {
  if (optionStyle() == OptionStyle::Cli || cliOption.rfind("--", 0) != 0) return cliOption;
  std::string keyword = cliOption.substr(2);
  for (char& c : keyword)
    if (c == '-') c = '_';
  return keyword + "=";
}

std::string flagName(const std::string& cliFlag) {
  if (optionStyle() == OptionStyle::Cli || cliFlag.rfind("--", 0) != 0) return cliFlag;
  return optionName(cliFlag) + "True";
}

std::string optionWithValue(const std::string& cliOption, const std::string& value, bool pythonQuotes) {
  if (optionStyle() == OptionStyle::Cli || cliOption.rfind("--", 0) != 0) return cliOption + " " + value;
  return optionName(cliOption) + (pythonQuotes ? "'" + value + "'" : value);
}

}  // namespace brdfcl
