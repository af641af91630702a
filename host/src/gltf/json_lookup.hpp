// Small helpers for the loader's passes over the raw glTF JSON (the compression extensions): a
// member lookup that never asserts on a const json, and the one-line failure with a JSON path.
#pragma once
#include <nlohmann/json.hpp>
#include <string>

#include "brdfcl/error.hpp"

namespace brdfcl::gltf::detail {

[[noreturn]] inline void fail(const std::string& source, const std::string& where, const std::string& message) {
  throw Error(source + ": " + where + ": " + message);
}

// nullptr where obj is no object or has no such key.
inline const nlohmann::json* member(const nlohmann::json& obj, const char* key) {
  if (!obj.is_object()) return nullptr;
  const auto it = obj.find(key);
  return it == obj.end() ? nullptr : &*it;
}

}  // namespace brdfcl::gltf::detail
