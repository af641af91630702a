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

// The message for a std::bad_alloc that reached the top: it names the input being read when
// one was (the file is then the likely cause), else suggests a smaller --size or --chunk.
std::string outOfMemoryMessage();

}  // namespace brdfcl
