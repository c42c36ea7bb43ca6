#include "scenes/generators/ullner_random.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <stdexcept>
#include <string>

#include "common/splitmix64.hpp"
#include "scenes/generators/random_rotation.hpp"

namespace rtsim::scenes {

namespace {

// --- View (assumption; the thesis gives only d_r = 1/2, seed 000 L654) ------------------------
// The eye sits at the centre of the y = 0 face of the modelling cube and looks straight in, so
// every primary ray starts on the cube's surface and travels through the modelling space. With
// a_t = 2 spread isotropically, a random line meets a_t / 2 = 1 surface per unit length, so a
// ray that would leave the cube after L travels on average 1 - e^-L before its first hit or its
// exit. Straight ahead L = 1 (0.63); a wide field of view sends the outer rays out through the
// side faces sooner. Idealised means (ray grid over the image): 90 degrees 0.60, 110 degrees
// 0.55, 130 degrees 0.51. Measured for N = 1000 (tests/scene_ullner_random_test.cpp, 128 x 128
// of the primary rays): 110 -> 0.57, 120 -> 0.55, 130 -> 0.53, 135 -> 0.52 (the placement
// leaves a slightly sparser layer at the faces). 130 degrees is the widest view still easy to
// read: d_r = 0.53, 51% of the primary rays hit.
constexpr Vec3 kUllnerRandomEye{0.5, 0.0, 0.5};
constexpr Vec3 kUllnerRandomLookAt{0.5, 1.0, 0.5};
constexpr Vec3 kUllnerRandomUp{0.0, 0.0, 1.0};
constexpr double kUllnerRandomFieldOfViewDeg = 130.0;
/// Primary rays start at the eye, on the face: no near clipping beyond rounding.
constexpr double kUllnerRandomHither = 1e-9;
constexpr int kUllnerRandomImageSize = 512;  ///< seed 000 L590
const Material kUllnerRandomMaterial{Color{1.0, 1.0, 1.0}, 1.0, 0.0, 0.0, 0.0, 1.0};

}  // namespace

Scene make_ullner_random(std::size_t polygon_count, std::uint64_t seed) {
  if (polygon_count < kUllnerRandomMinPolygons || polygon_count > kUllnerRandomMaxPolygons) {
    throw std::invalid_argument("make_ullner_random: polygon count must be in [" +
                                std::to_string(kUllnerRandomMinPolygons) + ", " +
                                std::to_string(kUllnerRandomMaxPolygons) + "]");
  }
  Scene scene;
  scene.name = "builtin:" + std::string(kUllnerRandomPrefix) + std::to_string(polygon_count);
  scene.has_camera = true;
  scene.modelling_space = Bounds{Vec3(0.0), Vec3(1.0)};
  scene.camera.from = kUllnerRandomEye;
  scene.camera.at = kUllnerRandomLookAt;
  scene.camera.up = kUllnerRandomUp;
  scene.camera.angle_deg = kUllnerRandomFieldOfViewDeg;
  scene.camera.hither = kUllnerRandomHither;
  scene.camera.width = kUllnerRandomImageSize;
  scene.camera.height = kUllnerRandomImageSize;
  scene.background = Color{0.0};
  scene.materials.push_back(kUllnerRandomMaterial);

  // a_p = a_t / n_p (L632: all polygons the same size); side s = sqrt(a_p), half side h.
  const double half = 0.5 * std::sqrt(kUllnerRandomTotalArea / static_cast<double>(polygon_count));
  SplitMix64 rng(seed);
  scene.polygons.resize(polygon_count);
  scene.primitives.resize(polygon_count);
  for (std::size_t k = 0; k < polygon_count; ++k) {
    const auto axes = random_rotation(rng);
    const Vec3 u = half * axes[0];
    const Vec3 v = half * axes[1];
    // Half extent per axis, h(|u_i| + |v_i|) <= h sqrt(2) <= 1/2 for N >= 4.
    Vec3 centre{0.0};
    for (int i = 0; i < 3; ++i) {
      const double extent = std::fabs(u[i]) + std::fabs(v[i]);
      centre[i] = rng.uniform(extent, 1.0 - extent);
    }
    // Counter-clockwise about u x v. The clamp only removes a possible last-bit rounding excess
    // (the exact vertices lie inside), so every vertex is in [0,1]^3 exactly.
    const auto in_cube = [](Vec3 p) { return glm::clamp(p, Vec3{0.0}, Vec3{1.0}); };
    Polygon& square = scene.polygons[k];
    square.vertices = {in_cube(centre - u - v), in_cube(centre + u - v), in_cube(centre + u + v),
                       in_cube(centre - u + v)};
    scene.primitives[k] = Primitive{PrimitiveKind::Polygon, static_cast<std::uint32_t>(k), 0, 0};
  }
  return scene;
}

std::optional<std::size_t> parse_ullner_random_name(std::string_view name) {
  if (name.substr(0, kUllnerRandomPrefix.size()) != kUllnerRandomPrefix) return std::nullopt;
  const std::string_view digits = name.substr(kUllnerRandomPrefix.size());
  // At most 9 digits: no overflow, and anything longer is out of range anyway (reported as such
  // by the caller through the value 10^9).
  // "0" is a number (out of range, which the caller says); "007" is no name.
  if (digits.empty() || (digits.size() > 1 && digits[0] == '0')) return std::nullopt;
  std::size_t n = 0;
  for (std::size_t i = 0; i < digits.size(); ++i) {
    const char c = digits[i];
    if (c < '0' || c > '9') return std::nullopt;
    if (i >= 9) {
      n = 1'000'000'000;
      continue;
    }
    n = 10 * n + static_cast<std::size_t>(c - '0');
  }
  return n;
}

}  // namespace rtsim::scenes
