#include "scenes/generators/default_scene.hpp"

#include <array>

namespace rtsim::scenes {

namespace {

// Materials (NFF f: colour, Kd, Ks, Shine, T, ior).
const Material kFloorLight{Color{0.90, 0.88, 0.82}, 0.85, 0.15, 20.0, 0.0, 1.0};
const Material kFloorDark{Color{0.18, 0.20, 0.26}, 0.85, 0.15, 20.0, 0.0, 1.0};
const Material kMirror{Color{0.95, 0.95, 0.95}, 0.10, 0.90, 300.0, 0.0, 1.0};
const Material kGlass{Color{1.0, 1.0, 1.0}, 0.05, 0.20, 400.0, 0.90, 1.5};
const Material kRedPlastic{Color{0.85, 0.15, 0.12}, 0.80, 0.30, 40.0, 0.0, 1.0};
const Material kBluePlastic{Color{0.15, 0.35, 0.85}, 0.80, 0.30, 40.0, 0.0, 1.0};
const Material kGold{Color{0.95, 0.72, 0.25}, 0.45, 0.55, 120.0, 0.0, 1.0};

enum MaterialId : std::uint32_t { kLight, kDark, kMirrorId, kGlassId, kRed, kBlue, kGoldId };

struct Ball {
  Vec3 centre;
  double radius;
  MaterialId material;
};

/// Spheres resting on the floor (z = radius): the mirror left-back (it shows the others and the
/// checkerboard), the glass right-front (the floor seen refracted through it), coloured balls.
constexpr std::array<Ball, 5> kBalls = {{
    {Vec3{-0.9, 0.9, 1.0}, 1.0, kMirrorId},
    {Vec3{1.1, -0.9, 0.75}, 0.75, kGlassId},
    {Vec3{-2.1, -0.7, 0.6}, 0.6, kRed},
    {Vec3{1.9, 1.5, 0.5}, 0.5, kBlue},
    {Vec3{-0.7, -1.9, 0.35}, 0.35, kGoldId},
}};

constexpr Vec3 kEye{1.5, -7.8, 4.2};
constexpr Vec3 kLookAt{0.0, -0.2, 0.5};
constexpr Vec3 kUp{0.0, 0.0, 1.0};
constexpr double kFieldOfViewDeg = 40.0;
constexpr Color kBackground{0.35, 0.55, 0.85};  // sky blue, seen in the mirror
constexpr std::array<Light, 2> kLights = {
    Light{Vec3{-4.0, -5.0, 8.0}, Color{0.9, 0.9, 0.85}},
    Light{Vec3{5.0, -3.0, 4.0}, Color{0.4, 0.4, 0.45}},
};

}  // namespace

Scene make_default_scene() {
  Scene scene;
  scene.name = "builtin:default";
  scene.has_camera = true;
  scene.camera.from = kEye;
  scene.camera.at = kLookAt;
  scene.camera.up = kUp;
  scene.camera.angle_deg = kFieldOfViewDeg;
  scene.camera.width = kDefaultImageSize;
  scene.camera.height = kDefaultImageSize;
  scene.background = kBackground;
  scene.lights.assign(kLights.begin(), kLights.end());
  scene.materials = {kFloorLight, kFloorDark, kMirror, kGlass, kRedPlastic, kBluePlastic, kGold};

  // Floor: kDefaultFloorTiles^2 quads in z = 0, counter-clockwise seen from above (+z).
  const double tile = 2.0 * kDefaultFloorHalfWidth / kDefaultFloorTiles;
  for (int j = 0; j < kDefaultFloorTiles; ++j) {
    for (int i = 0; i < kDefaultFloorTiles; ++i) {
      const double x0 = -kDefaultFloorHalfWidth + i * tile;
      const double y0 = -kDefaultFloorHalfWidth + j * tile;
      Polygon quad;
      quad.vertices = {Vec3{x0, y0, 0.0}, Vec3{x0 + tile, y0, 0.0}, Vec3{x0 + tile, y0 + tile, 0.0},
                       Vec3{x0, y0 + tile, 0.0}};
      scene.polygons.push_back(std::move(quad));
      scene.primitives.push_back(Primitive{PrimitiveKind::Polygon,
                                           static_cast<std::uint32_t>(scene.polygons.size() - 1),
                                           ((i + j) % 2 == 0) ? kLight : kDark, 0});
    }
  }
  for (const Ball& b : kBalls) {
    scene.spheres.push_back(Sphere{b.centre, b.radius});
    scene.primitives.push_back(Primitive{PrimitiveKind::Sphere,
                                         static_cast<std::uint32_t>(scene.spheres.size() - 1),
                                         b.material, 0});
  }
  return scene;
}

}  // namespace rtsim::scenes
