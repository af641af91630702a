// The sheen albedo bake with its kernel file as a parameter: "sheen_albedo.cl" bakes the cached
// table (nodes mu = s^2, r = t^2), "lut.cl" the exported sheen LUTs (nodes uniform in mu and r).
#pragma once
#include <string>

#include "brdfcl/evaluator.hpp"

namespace brdfcl {

SheenAlbedoTable bakeSheenAlbedoFrom(Runtime& rt, const std::string& kernelFile, SheenDistribution d,
                                     SheenVisibility v, std::size_t size, int nodesPerPanel);

}  // namespace brdfcl
