#include "firmware/kernels/sphere.hpp"

namespace rtsim::kernels {

std::optional<SphereKernel> SphereKernel::from(const scenes::Sphere& sphere, std::string* why) {
  auto reject = [why](const char* reason) -> std::optional<SphereKernel> {
    if (why != nullptr) *why = reason;
    return std::nullopt;
  };
  if (!is_finite(sphere.center)) return reject("sphere centre is not finite");
  if (!std::isfinite(sphere.radius)) return reject("sphere radius is not finite");
  if (!(sphere.radius > 0.0)) return reject("sphere radius is not positive");
  SphereKernel k;
  k.center_ = sphere.center;
  k.radius_ = sphere.radius;
  k.r2_ = sphere.radius * sphere.radius;
  if (!std::isfinite(k.r2_) || !(k.r2_ > 0.0)) {
    return reject("sphere radius squared overflows or underflows double");
  }
  return k;
}

}  // namespace rtsim::kernels
