#include "scenes/generators/ullner_sheets.hpp"

#include <algorithm>
#include <cmath>
#include <string>

#include "scenes/generators/name_number.hpp"

namespace rtsim::scenes {
namespace {

/// A sheet y = y0 + a (x - 1/2) + b (z - 1/2) over x, z in [0, 1]. Tilts a, b: small, so the
/// sheets stay inside the cube and never lie on a grid plane (assumption: any small tilt; the
/// area grows by sqrt(1 + a^2 + b^2) - 1 < 0.5%).
struct Sheet {
  double y0, a, b;
  Vec3 at(double x, double z) const { return {x, y0 + a * (x - 0.5) + b * (z - 0.5), z}; }
};
constexpr Sheet kSheets[2] = {{0.5, 0.06, 0.04}, {0.8, -0.05, 0.07}};

/// Eye outside the cube on the axis through the middle of the y = 0 face, 4.5 away, looking
/// along +y; 11 degrees keeps every primary ray inside the face and on the first sheet (which
/// spans 11.4 degrees from here). Far away, so the rays run nearly along the axis as the
/// model's n_d = (n_s - 1) d_r + 1 (L614) assumes: a wider view adds subvolume crossings.
constexpr Vec3 kEye{0.5, -4.5, 0.5};
constexpr Vec3 kAt{0.5, 0.5, 0.5};
constexpr double kAngleDeg = 11.0;
constexpr int kImageSize = 512;  ///< seed 000 L590

/// Edge i of k along a sheet: i / k, moved by up to 15% of a cell by a golden-ratio sequence so
/// that no edge lies on a grid plane j / n_s for the subdivisions of interest (a polygon touching
/// a plane is listed in both subvolumes, which the model does not count; with edges at i / 22,
/// every other one would lie on a plane of an 11-division grid).
double edge(std::size_t i, std::size_t k) {
  if (i == 0 || i == k) return static_cast<double>(i) / static_cast<double>(k);
  const double jitter = std::fmod(static_cast<double>(i) * 0.6180339887498949, 1.0) - 0.5;
  return (static_cast<double>(i) + 0.3 * jitter) / static_cast<double>(k);
}

}  // namespace

Scene make_ullner_sheets(std::size_t polygon_count, bool lit) {
  const auto k = static_cast<std::size_t>(
      std::max(1.0, std::round(std::sqrt(static_cast<double>(polygon_count) / 2.0))));
  Scene scene;
  scene.name = "builtin:" + std::string(lit ? kUllnerSheetsLitPrefix : kUllnerSheetsPrefix) +
               std::to_string(polygon_count);
  scene.has_camera = true;
  scene.camera.from = kEye;
  scene.camera.at = kAt;
  scene.camera.up = Vec3(0.0, 0.0, 1.0);
  scene.camera.angle_deg = kAngleDeg;
  scene.camera.hither = 1e-3;
  scene.camera.width = kImageSize;
  scene.camera.height = kImageSize;
  scene.modelling_space = Bounds{Vec3(0.0), Vec3(1.0)};
  // One white, opaque, non-reflective material, no lights: "without lighting effects" (L590).
  scene.materials.push_back(Material{Color(1.0), 1.0, 0.0, 0.0, 0.0, 1.0});
  // The lit variant: one light at the eye, so every hit's shadow ray runs back unoccluded.
  if (lit) scene.lights.push_back(Light{kEye, Color(1.0)});
  scene.polygons.reserve(2 * k * k);
  scene.primitives.reserve(2 * k * k);
  for (const Sheet& sheet : kSheets) {
    for (std::size_t j = 0; j < k; ++j) {
      for (std::size_t i = 0; i < k; ++i) {
        const double x0 = edge(i, k), x1 = edge(i + 1, k);
        const double z0 = edge(j, k), z1 = edge(j + 1, k);
        Polygon q;
        // Counter-clockwise seen from the eye (normal (a, -1, b) points toward -y).
        q.vertices = {sheet.at(x0, z0), sheet.at(x1, z0), sheet.at(x1, z1), sheet.at(x0, z1)};
        scene.primitives.push_back(Primitive{
            PrimitiveKind::Polygon, static_cast<std::uint32_t>(scene.polygons.size()), 0, 0});
        scene.polygons.push_back(std::move(q));
      }
    }
  }
  return scene;
}

std::optional<std::size_t> parse_ullner_sheets_name(std::string_view name, bool* lit) {
  const bool is_lit = name.substr(0, kUllnerSheetsLitPrefix.size()) == kUllnerSheetsLitPrefix;
  if (lit) *lit = is_lit;
  return number_after_prefix(name, is_lit ? kUllnerSheetsLitPrefix : kUllnerSheetsPrefix);
}

}  // namespace rtsim::scenes
