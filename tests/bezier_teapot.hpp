#pragma once
// Test helpers shared by the Bezier tests and benchmark: a tiny reader of the .bpt format (the
// real scene reader lives in scenes/, written separately) and a camera that frames the teapot.
// Format (shared/scenes/README.md): first line the patch count, then per patch a line "3 3" and
// 16 lines "x y z", row by row.
#include <cmath>
#include <fstream>
#include <stdexcept>
#include <string>
#include <vector>

#include "firmware/bounds.hpp"
#include "firmware/math.hpp"
#include "firmware/ray.hpp"
#include "firmware/scene.hpp"

namespace rtsim::bezier_test {

inline std::vector<scenes::BezierPatch> read_bpt(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw std::runtime_error("cannot open " + path);
  int count = 0;
  in >> count;
  std::vector<scenes::BezierPatch> patches(static_cast<std::size_t>(count));
  for (auto& p : patches) {
    int m = 0, n = 0;
    in >> m >> n;
    if (m != 3 || n != 3) throw std::runtime_error(path + ": expected a '3 3' patch");
    for (auto& c : p.control) in >> c.x >> c.y >> c.z;
  }
  if (!in) throw std::runtime_error(path + ": truncated");
  return patches;
}

inline std::vector<scenes::BezierPatch> teapot() {
  return read_bpt(std::string(RTSIM_SHARED_DIR) + "/scenes/teapot.bpt");
}

inline Bounds patches_bounds(const std::vector<scenes::BezierPatch>& patches) {
  Bounds b;
  for (const auto& p : patches)
    for (const auto& c : p.control) b.extend(c);
  return b;
}

/// A pinhole camera looking at the centre of `box` from direction `from_dir` and
/// `distance_in_radii` times the box's half-diagonal away; zoom 1 has the box's bounding sphere
/// just in view, larger zooms crop. ray(i, j) for pixel (i, j) of an n x n image (j upward).
struct FramingCamera {
  Vec3 eye, forward, right, up;
  double half_extent = 1.0;  ///< image-plane half size at distance 1
  int n = 1;

  FramingCamera(const Bounds& box, Vec3 from_dir, int pixels, double distance_in_radii = 2.0,
                double zoom = 1.0)
      : n(pixels) {
    const Vec3 center = box.center();
    const double radius = 0.5 * glm::length(box.extent());
    from_dir = glm::normalize(from_dir);
    const double distance = distance_in_radii * radius;
    eye = center + distance * from_dir;
    forward = -from_dir;
    right = glm::normalize(glm::cross(forward, Vec3(0, 0, 1)));
    up = glm::cross(right, forward);
    half_extent = radius / std::sqrt(distance * distance - radius * radius) / zoom;
  }
  Ray ray(int i, int j) const {
    const double x = ((i + 0.5) / n * 2.0 - 1.0) * half_extent;
    const double y = ((j + 0.5) / n * 2.0 - 1.0) * half_extent;
    return Ray{eye, glm::normalize(forward + x * right + y * up)};
  }
};

}  // namespace rtsim::bezier_test
