#include "scenes/generators/ullner_cubes.hpp"

#include <array>
#include <cmath>
#include <stdexcept>

#include "common/splitmix64.hpp"
#include "scenes/generators/random_rotation.hpp"

namespace rtsim::scenes {

namespace {

// --- Look (assumption; the thesis gives no view, note 000 §7.5 S3) ---------------------------
// Eye outside the modelling cube, above and to the front-right, looking at its centre. The cube
// centres keep a half-diagonal margin, so the cubes fill the inner ~0.83 of the modelling cube;
// 32 degrees frames that cloud (a 36.6 degree field would hold the whole modelling cube's
// bounding sphere, radius 0.866 at distance 2.76, and leave the cubes small).
constexpr Vec3 kUllnerEye{2.1, -1.35, 1.7};
constexpr Vec3 kUllnerLookAt{0.5, 0.5, 0.5};
constexpr Vec3 kUllnerUp{0.0, 0.0, 1.0};
constexpr double kUllnerFieldOfViewDeg = 32.0;
constexpr int kUllnerImageSize = 512;  ///< Ullner's working resolution, seed 000 L590
constexpr Color kUllnerBackground{0.08, 0.08, 0.1};
constexpr std::array<Light, 2> kUllnerLights = {
    Light{Vec3{3.0, -2.0, 4.0}, Color{0.9, 0.9, 0.85}},
    Light{Vec3{-1.5, -2.5, 1.0}, Color{0.3, 0.3, 0.35}},
};
/// Matte-ish plastics (Ullner's pictures are diffuse with highlights); drawn per cube.
const std::array<Material, 4> kUllnerPalette = {
    Material{Color{0.90, 0.30, 0.20}, 0.8, 0.2, 25.0, 0.0, 1.0},
    Material{Color{0.25, 0.55, 0.90}, 0.8, 0.2, 25.0, 0.0, 1.0},
    Material{Color{0.95, 0.85, 0.35}, 0.8, 0.2, 25.0, 0.0, 1.0},
    Material{Color{0.35, 0.80, 0.45}, 0.8, 0.2, 25.0, 0.0, 1.0},
};

/// Corners of the unit-half cube: bit 0 -> x, bit 1 -> y, bit 2 -> z (0 = -1/2, 1 = +1/2).
/// Faces as corner indices, counter-clockwise seen from outside (right-hand rule gives the
/// outward normal): -x, +x, -y, +y, -z, +z.
constexpr std::array<std::array<int, 4>, 6> kCubeFaces = {{
    {0, 4, 6, 2},  // -x
    {1, 3, 7, 5},  // +x
    {0, 1, 5, 4},  // -y
    {2, 6, 7, 3},  // +y
    {0, 2, 3, 1},  // -z
    {4, 5, 7, 6},  // +z
}};

}  // namespace

Scene make_ullner_cubes(std::uint64_t seed, int cube_count) {
  if (cube_count < 1) throw std::invalid_argument("make_ullner_cubes: cube_count must be >= 1");
  Scene scene;
  scene.name = "builtin:ullner-cubes";
  scene.has_camera = true;
  scene.camera.from = kUllnerEye;
  scene.camera.at = kUllnerLookAt;
  scene.camera.up = kUllnerUp;
  scene.camera.angle_deg = kUllnerFieldOfViewDeg;
  scene.camera.width = kUllnerImageSize;
  scene.camera.height = kUllnerImageSize;
  scene.background = kUllnerBackground;
  scene.lights.assign(kUllnerLights.begin(), kUllnerLights.end());
  scene.materials.assign(kUllnerPalette.begin(), kUllnerPalette.end());

  SplitMix64 rng(seed);
  const double half = 0.5 * kUllnerCubeEdge;
  const double margin = half * std::sqrt(3.0);  // half diagonal: any orientation stays inside
  const auto n = static_cast<std::size_t>(cube_count);
  scene.polygons.reserve(6 * n);
  scene.primitives.reserve(6 * n);
  for (std::size_t cube = 0; cube < n; ++cube) {
    const Vec3 centre{rng.uniform(margin, 1.0 - margin), rng.uniform(margin, 1.0 - margin),
                      rng.uniform(margin, 1.0 - margin)};
    const auto axes = random_rotation(rng);
    std::array<Vec3, 8> corners;
    for (int i = 0; i < 8; ++i) {
      const double sx = (i & 1) ? half : -half;
      const double sy = (i & 2) ? half : -half;
      const double sz = (i & 4) ? half : -half;
      corners[static_cast<std::size_t>(i)] = centre + sx * axes[0] + sy * axes[1] + sz * axes[2];
    }
    const auto material = static_cast<std::uint32_t>(rng.below(kUllnerPalette.size()));
    for (const auto& face : kCubeFaces) {
      Polygon quad;
      for (int idx : face) quad.vertices.push_back(corners[static_cast<std::size_t>(idx)]);
      scene.polygons.push_back(std::move(quad));
      scene.primitives.push_back(Primitive{PrimitiveKind::Polygon,
                                           static_cast<std::uint32_t>(scene.polygons.size() - 1),
                                           material, 0});
    }
  }
  return scene;
}

}  // namespace rtsim::scenes
