// The one exception type brdfcl throws for bad input and environment problems, with its kind.
// The CLI prints what() as a single line and exits with exitCode (2 for anything the user can fix).
#pragma once
#include <stdexcept>
#include <string>

namespace brdfcl {

// `s` with every byte that is not part of valid UTF-8, and every control character but newline
// and tab, written as \xNN: a message quoting a file's bytes stays readable text on a terminal
// and decodes as a Python str.
std::string escapeMessage(const std::string& s);

// Who can fix an error, for callers that react by kind (the Python module maps each to one of
// Python's built-in exception classes, docs/python.md).
enum class ErrorKind {
  Input,        // a file, option or argument: the user fixes it
  Environment,  // the machine: no OpenCL platform or device, an unusable cache folder
  Device,       // an OpenCL call or kernel build failed on the device
  Memory,       // host or device memory ran out
  Internal,     // a broken invariant in brdfcl itself (exit code 3)
};

// "input", "environment", "device", "memory" or "internal".
const char* toString(ErrorKind kind);

class Error : public std::runtime_error {
 public:
  // Exit code 3 marks brdfcl's own faults, so it implies ErrorKind::Internal; anything else is input.
  explicit Error(const std::string& message, int exitCode = 2)
      : std::runtime_error(escapeMessage(message)),
        exitCode_(exitCode),
        kind_(exitCode == 3 ? ErrorKind::Internal : ErrorKind::Input) {}
  Error(ErrorKind kind, const std::string& message, int exitCode = 2)
      : std::runtime_error(escapeMessage(message)), exitCode_(exitCode), kind_(kind) {}
  int exitCode() const { return exitCode_; }
  ErrorKind kind() const { return kind_; }

 private:
  int exitCode_;
  ErrorKind kind_;
};

// The message for a std::bad_alloc that reached the top: it names the input being read when
// one was (the file is then the likely cause), else suggests a smaller --size or --chunk.
std::string outOfMemoryMessage();

}  // namespace brdfcl
