// Opening the files that a file names inside itself (glTF buffer and image URIs, a scene's
// environment path): confined to the naming file's folder, regular files only, read with a size
// bound taken from fstat. The rule is in docs/gltf.md ("Files an asset names").
#pragma once
#include <cstdint>
#include <string>

namespace brdfcl::detail {

// The scheme of a URI ("http" for "http://x/y"), or "" for a relative reference. A file name
// with a colon after its first character is taken as a scheme too (as RFC 3986 parses it).
std::string uriScheme(const std::string& uri);

// Percent-decoding as tinygltf does it ('+' is a space), so that a decoded name matches the path
// tinygltf hands to the file callbacks.
std::string uriDecoded(const std::string& uri);

// Whether `name` (decoded), taken relative to a folder, stays inside it: not absolute, and no
// ".." above the folder once "." and ".." are taken by name ("a/../b" is "b").
bool staysInside(const std::string& name);

// What opening or reading a named file came to. The refusals (Outside, Link, NotRegular) are
// decided before the file is read and say nothing about a target outside the folder.
struct Opened {
  enum class Outcome {
    Ok,
    Outside,     // absolute, or ".." above the folder
    Link,        // a symbolic link on the way (confined opening follows none)
    NotRegular,  // a directory, FIFO, device or socket
    TooSmall,    // fewer bytes than the caller needs (`size` says how many)
    TooLarge,    // more bytes than the caller reads (`size` says how many)
    Unreadable,  // `error` says why (ENOENT, EACCES, ...): only for files inside the folder or allowed
  };
  Outcome outcome = Outcome::Ok;
  int error = 0;
  std::uint64_t size = 0;
};

struct OpenRules {
  // false: `name` must stay inside `dir` and every component is opened with O_NOFOLLOW from the
  // folder's own descriptor (the folder itself may be reached through a link). true: absolute
  // names, ".." and links are followed; non-regular files are still refused.
  bool allowOutside = false;
  std::uint64_t atLeast = 0;                 // fewer bytes: TooSmall
  std::uint64_t sizeAtMost = UINT64_MAX;     // more bytes: TooLarge
  std::uint64_t readAtMost = UINT64_MAX;     // bytes read from the start (a buffer's byteLength)
};

// Opens `name` (decoded; relative to `dir`, "" = the working directory) for reading and returns
// its descriptor (O_CLOEXEC, a regular file) with outcome Ok, or -1 with the reason. The size
// rules are checked against fstat.
int openInside(const std::string& dir, const std::string& name, const OpenRules& rules, Opened& result);

// openInside, then reads min(size, readAtMost) bytes into `out`.
Opened readInside(const std::string& dir, const std::string& name, const OpenRules& rules, std::string& out);

}  // namespace brdfcl::detail
