// Where an output path really leads (stdout, a FIFO or device, or a regular file at the end of
// its symlinks) and the pieces writers use to write there: temporaries, streams, NPY headers.
#pragma once
#include <cstddef>
#include <string>

namespace brdfcl::detail {

enum class OutputKind {
  Stdout,  // the path "-" (or /dev/stdout): file descriptor 1
  Stream,  // an existing FIFO, character device or other non-regular file: written in place
  File,    // a regular file (existing or not): written to a temporary, renamed into place
};

struct OutputTarget {
  OutputKind kind = OutputKind::File;
  // File: the path after following every symlink (relative link targets against the link's
  // directory), where the temporary and the rename happen. Stream: the user's path.
  std::string path;
};

// True when `userPath` is written in place rather than through a temporary: "-", /dev/stdout, an
// existing FIFO, character device or other non-regular file (not a directory). Its name says
// nothing about its format, so commands give it the format their option implies.
bool isStreamTarget(const std::string& userPath);

// Throws Error "cannot write '<path>': ..." for a directory, a name that is not a file name and
// a symlink loop.
OutputTarget resolveOutput(const std::string& userPath);
// The same with `head` in place of "cannot write '<path>': " (checkOutputPath's "--out '<path>':
// cannot write: ").
OutputTarget resolveOutputWithHead(const std::string& userPath, const std::string& head);

// The end of the results writers' unknown-extension message.
inline constexpr const char* kResultsExtensionHint = "unknown extension; use .csv or .npy (- writes CSV to stdout)";

// The lower-case extension (".csv"), ".csv" for "-" and for an extensionless Stream target
// (/dev/stdout, a FIFO named "results"): those get the writer's text format.
std::string outputExtension(const std::string& userPath, const OutputTarget& target);

// An empty, registered temporary beside `finalPath` (named as temporaries.hpp says), after
// removing the directory's stale temporaries; when it replaces a regular file, with that file's
// permission bits and owner (where allowed). Errors name `userPath`.
std::string createTemporary(const std::string& finalPath, const std::string& userPath);
// A registered temporary (mode 0600) in the system temp directory, for output spooled before it
// is streamed.
std::string createSpool(const std::string& userPath);
// rename() into place, then forget the temporary; throws Error naming `userPath`.
void commitTemporary(const std::string& tmp, const std::string& finalPath, const std::string& userPath);
// unlink() and forget; never throws.
void removeTemporary(const std::string& tmp);

// A descriptor to write a Stdout or Stream target (1 for stdout: not to be closed).
int openStream(const OutputTarget& target, const std::string& userPath);
void closeStream(int fd, const OutputTarget& target, const std::string& userPath);
void writeAll(int fd, const void* data, std::size_t size, const std::string& userPath);
// Copies the file `from` to `fd`.
void copyFile(const std::string& from, int fd, const std::string& userPath);

// NPY v1.0 header of float32 data with the given shape tuple ("(12, 3)"), padded to 128 bytes
// so that a streamed file can reserve it and patch the row count in place.
std::string npyHeader(const std::string& shape);
// The same for a (rows, cols) matrix.
std::string npyHeader(std::size_t rows, std::size_t cols);

}  // namespace brdfcl::detail
