#include "firmware/kernels/cone.hpp"

namespace rtsim::kernels {

std::optional<ConeKernel> ConeKernel::from(const scenes::Cone& cone, std::string* why) {
  auto reject = [why](const char* reason) -> std::optional<ConeKernel> {
    if (why != nullptr) *why = reason;
    return std::nullopt;
  };
  if (!is_finite(cone.base) || !is_finite(cone.apex)) return reject("cone end is not finite");
  if (!std::isfinite(cone.base_radius) || !std::isfinite(cone.apex_radius)) {
    return reject("cone radius is not finite");
  }
  const double r0 = std::fabs(cone.base_radius);  // NFF: negative = seen from inside
  const double r1 = std::fabs(cone.apex_radius);
  if (r0 == 0.0 && r1 == 0.0) return reject("both cone radii are zero (a line, no surface)");
  const Vec3 axis = cone.apex - cone.base;
  const double h = glm::length(axis);
  const double scale = std::fmax(max_abs_component(cone.base), max_abs_component(cone.apex));
  if (!(h > kConeCoincidentRelative * scale) || !(h > 0.0) || !std::isfinite(h)) {
    return reject("cone base and apex coincide");
  }
  ConeKernel k;
  k.base_ = cone.base;
  k.apex_ = cone.apex;
  k.centre_ = 0.5 * (cone.base + cone.apex);
  k.w_ = axis / h;
  // Orthonormal frame: cross the axis with the coordinate axis it is least aligned with.
  const Vec3 aw = glm::abs(k.w_);
  const Vec3 helper = (aw.x <= aw.y && aw.x <= aw.z) ? Vec3(1, 0, 0)
                      : (aw.y <= aw.z)               ? Vec3(0, 1, 0)
                                                     : Vec3(0, 0, 1);
  k.u_ = glm::normalize(glm::cross(k.w_, helper));
  k.v_ = glm::cross(k.w_, k.u_);
  k.r0_ = r0;
  k.r1_ = r1;
  k.k_ = (r1 - r0) / h;
  k.height_ = h;
  k.half_height_ = 0.5 * h;
  k.inv_height_ = 1.0 / h;
  const double s = 1.0 / std::sqrt(1.0 + k.k_ * k.k_);
  k.normal_radial_scale_ = s;
  k.normal_axial_ = -k.k_ * s;
  if (!std::isfinite(k.k_) || !std::isfinite(k.inv_height_) || !std::isfinite(s)) {
    return reject("cone too slender or too flat for double precision");
  }
  return k;
}

Bounds ConeKernel::bounds() const {
  // The lateral surface is inside the convex hull of its two end circles. A circle of radius r
  // with unit axis w extends r * sqrt(1 - w_i^2) along coordinate i.
  const Vec3 ext(std::sqrt(std::fmax(0.0, 1.0 - w_.x * w_.x)),
                 std::sqrt(std::fmax(0.0, 1.0 - w_.y * w_.y)),
                 std::sqrt(std::fmax(0.0, 1.0 - w_.z * w_.z)));
  Bounds b;
  b.extend(base_ - r0_ * ext);
  b.extend(base_ + r0_ * ext);
  b.extend(apex_ - r1_ * ext);
  b.extend(apex_ + r1_ * ext);
  return b;
}

}  // namespace rtsim::kernels
