// The samples harnesses' shared check: a file read whole (readSamples) and streamed in small
// chunks (SampleStream, as `brdfcl eval` reads it) must give the same rows bit for bit, or the
// same one-line error; any difference aborts, so libFuzzer keeps the input.
#pragma once
#include <cstddef>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>

#include "brdfcl/io.hpp"
#include "fuzz_support.hpp"

namespace brdfcl::fuzz {

struct SamplesOutcome {
  Samples rows;
  std::string error;  // empty when the file was accepted
};

inline bool sameRows(const Samples& a, const Samples& b) {
  const auto same = [](const auto& x, const auto& y) {
    return x.size() == y.size() && (x.empty() || std::memcmp(x.data(), y.data(), x.size() * sizeof(x[0])) == 0);
  };
  return same(a.material, b.material) && same(a.L, b.L) && same(a.V, b.V);
}

inline void expectStreamMatchesWhole(const std::string& path, std::size_t materialCount, bool optional,
                                     std::size_t chunk) {
  SamplesOutcome whole, streamed;
  expectCleanRefusal([&] {
    try {
      whole.rows = readSamples(path, materialCount, optional);
    } catch (const Error& e) {
      whole.error = e.what();
      throw;
    }
  });
  expectCleanRefusal([&] {
    try {
      SampleStream stream(path, materialCount, optional);
      Samples part;
      while (stream.next(chunk, part)) {
        if (part.size() == 0 || part.size() > chunk) {
          std::fprintf(stderr, "fuzz harness: a chunk of %zu rows for at most %zu\n", part.size(), chunk);
          std::abort();
        }
        streamed.rows.material.insert(streamed.rows.material.end(), part.material.begin(), part.material.end());
        streamed.rows.L.insert(streamed.rows.L.end(), part.L.begin(), part.L.end());
        streamed.rows.V.insert(streamed.rows.V.end(), part.V.begin(), part.V.end());
      }
    } catch (const Error& e) {
      streamed.error = e.what();
      throw;
    }
  });
  if (whole.error != streamed.error || (whole.error.empty() && !sameRows(whole.rows, streamed.rows))) {
    std::fprintf(stderr, "fuzz harness: streamed in chunks of %zu != read whole\n  whole: [%s] %zu rows\n  streamed: [%s] %zu rows\n",
                 chunk, whole.error.c_str(), whole.rows.size(), streamed.error.c_str(), streamed.rows.size());
    std::abort();
  }
}

}  // namespace brdfcl::fuzz
