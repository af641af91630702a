// The engine each parity profile reproduces and the source it is pinned to (docs/profiles.md),
// for output that names what a result matches: `compare`'s report, `render`/`shade --profile`.
#pragma once
#include <string>

#include "brdfcl/material.hpp"

namespace brdfcl {

struct EngineVersion {
  const char* engine;   // "MaterialX gltf_pbr"
  const char* version;  // the release and commits docs/profiles.md pins, never empty
};

// Engines change their maths between commits, so a profile's numbers hold for its pin only.
EngineVersion profileEngineVersion(Profile p);

// One line: "materialx: MaterialX gltf_pbr 1.39.5+ at commit 4177b2cb (...)".
std::string describeProfile(Profile p);

}  // namespace brdfcl
