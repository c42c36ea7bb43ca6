#pragma once
// Vector types shared by every layer. The functional renderer and the firmware tasks compute in
// double precision; kernels that model 32-bit hardware arithmetic are templated on the scalar
// type so the same code can be run in float and compared against double.
#include <cmath>
#include <glm/glm.hpp>
#include <limits>

namespace rtsim {

using Vec3 = glm::dvec3;
using Color = glm::dvec3;

inline constexpr double kInfinity = std::numeric_limits<double>::infinity();
inline constexpr double kPi = 3.14159265358979323846;

template <typename T>
using Vec3T = glm::vec<3, T, glm::defaultp>;

/// Largest absolute component, the scale used for relative tolerances.
inline double max_abs_component(const Vec3& v) {
  return std::fmax(std::fabs(v.x), std::fmax(std::fabs(v.y), std::fabs(v.z)));
}

inline bool is_finite(const Vec3& v) {
  return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z);
}

}  // namespace rtsim
