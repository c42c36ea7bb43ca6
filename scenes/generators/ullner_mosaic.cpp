#include "scenes/generators/ullner_mosaic.hpp"

#include <cmath>
#include <string>

#include "scenes/generators/name_number.hpp"

namespace rtsim::scenes {

namespace {
/// The sheet is the unit square at z = 0 seen from 2 units in front of its centre, the view's
/// angle just taking it in (2 atan(1/4)).
constexpr double kEyeDistance = 2.0;
constexpr int kImageSize = 512;  ///< seed 000 L1551: 512 lines
}  // namespace

Scene make_ullner_mosaic(std::size_t columns) {
  Scene scene;
  scene.name = "builtin:" + std::string(kUllnerMosaicPrefix) + std::to_string(columns);
  scene.has_camera = true;
  scene.camera.from = Vec3(0.5, 0.5, kEyeDistance);
  scene.camera.at = Vec3(0.5, 0.5, 0.0);
  scene.camera.up = Vec3(0.0, 1.0, 0.0);
  scene.camera.angle_deg = 2.0 * std::atan(0.5 / kEyeDistance) * 180.0 / M_PI;
  scene.camera.hither = 1e-3;
  scene.camera.width = kImageSize;
  scene.camera.height = kImageSize;
  scene.modelling_space = Bounds{Vec3(0.0, 0.0, -0.5), Vec3(1.0, 1.0, 0.5)};
  // Two materials in a checkerboard, so the columns show.
  scene.materials.push_back(Material{Color(1.0), 1.0, 0.0, 0.0, 0.0, 1.0});
  scene.materials.push_back(Material{Color(0.3, 0.5, 0.9), 1.0, 0.0, 0.0, 0.0, 1.0});
  const std::size_t rows = kUllnerMosaicRows;
  scene.polygons.reserve(columns * rows);
  scene.primitives.reserve(columns * rows);
  for (std::size_t j = 0; j < rows; ++j)
    for (std::size_t i = 0; i < columns; ++i) {
      const double x0 = static_cast<double>(i) / columns, x1 = static_cast<double>(i + 1) / columns;
      const double y0 = static_cast<double>(j) / rows, y1 = static_cast<double>(j + 1) / rows;
      Polygon q;
      // Counter-clockwise seen from the eye (+z).
      q.vertices = {Vec3(x0, y0, 0.0), Vec3(x1, y0, 0.0), Vec3(x1, y1, 0.0), Vec3(x0, y1, 0.0)};
      scene.primitives.push_back(Primitive{PrimitiveKind::Polygon,
                                           static_cast<std::uint32_t>(scene.polygons.size()),
                                           static_cast<std::uint32_t>((i + j) % 2), 0});
      scene.polygons.push_back(std::move(q));
    }
  return scene;
}

std::optional<std::size_t> parse_ullner_mosaic_name(std::string_view name) {
  return number_after_prefix(name, kUllnerMosaicPrefix);
}

}  // namespace rtsim::scenes
