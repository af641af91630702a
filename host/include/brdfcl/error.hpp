// The one exception type brdfcl throws for bad input and environment problems.
// The CLI prints what() as a single line and exits with exitCode (2 for anything the user can fix).
#pragma once
#include <stdexcept>
#include <string>

namespace brdfcl {

// `s` with every byte that is not part of valid UTF-8, and every control character but newline
// and tab, written as \xNN: a message quoting a file's bytes stays readable text on a terminal
// and decodes as a Python str.
std::string escapeMessage(const std::string& s);

class Error : public std::runtime_error {
 public:
  explicit Error(const std::string& message, int exitCode = 2)
      : std::runtime_error(escapeMessage(message)), exitCode_(exitCode) {}
  int exitCode() const { return exitCode_; }

 private:
  int exitCode_;
};

// The message for a std::bad_alloc that reached the top: it names the input being read when
// one was (the file is then the likely cause), else suggests a smaller --size or --chunk.
std::string outOfMemoryMessage();

}  // namespace brdfcl
