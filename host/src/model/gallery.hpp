// The built-in material gallery: the seeds' example materials and a few everyday ones, as glTF
// material JSON so that they exercise the same reader as user files.
#pragma once
#include <string>
#include <vector>

#include "brdfcl/material.hpp"

namespace brdfcl {

const std::string& galleryJson();
std::vector<MaterialParams> gallery();

}  // namespace brdfcl
