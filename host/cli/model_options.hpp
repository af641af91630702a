// The options that choose which BRDF a command evaluates (--profile and the spec's sheen
// variants), registered once for every command that evaluates f.
#pragma once
#include <memory>
#include <string>

#include <CLI/CLI.hpp>

#include "brdfcl/material.hpp"

namespace brdfcl::cli {

struct ModelArgs {
  std::string profile = "spec", visibility = "charlie", distribution = "charlie", scaling = "min";
};

// --profile, --sheen-visibility, --sheen-distribution, --sheen-scaling.
void addModelOptions(CLI::App* cmd, ModelArgs& args);

// The options they name (lobe All); throws brdfcl::Error on an unknown value.
EvalOptions modelOptions(const ModelArgs& args);

}  // namespace brdfcl::cli
