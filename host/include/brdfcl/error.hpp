// The one exception type brdfcl throws for bad input and environment problems.
// The CLI prints what() as a single line and exits with exitCode (2 for anything the user can fix).
#pragma once
#include <stdexcept>
#include <string>

namespace brdfcl {

class Error : public std::runtime_error {
 public:
  explicit Error(const std::string& message, int exitCode = 2)
      : std::runtime_error(message), exitCode_(exitCode) {}
  int exitCode() const { return exitCode_; }

 private:
  int exitCode_;
};

}  // namespace brdfcl
