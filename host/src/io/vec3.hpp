// Imath's 3-vectors for the private geometry (cameras, scene directions, glTF surfaces and
// tangents): the conversions to and from the std::array<T, 3> that the public headers hold, and
// the length every caller normalizes with.
#pragma once
#include <ImathVec.h>

#include <array>
#include <cmath>

namespace brdfcl::detail {

template <class T>
Imath::Vec3<T> toVec3(const std::array<T, 3>& a) {
  return Imath::Vec3<T>(a[0], a[1], a[2]);
}

template <class T>
std::array<T, 3> toArray(const Imath::Vec3<T>& v) {
  return {v.x, v.y, v.z};
}

// sqrt(v ^ v). Imath's length() switches to a rescaled formula for tiny vectors (lengthTiny) and
// its normalize() divides where some callers multiply by the reciprocal; the cameras, tangents and
// surfaces keep this exact arithmetic so that every image and G-buffer stays bit for bit the same.
template <class T>
T norm(const Imath::Vec3<T>& v) {
  return std::sqrt(v ^ v);
}

}  // namespace brdfcl::detail
