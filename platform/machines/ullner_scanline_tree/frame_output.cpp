#include "platform/machines/ullner_scanline_tree/frame_output.hpp"

#include <cmath>

namespace rtsim::platform::ullner_scanline_tree {

void deliver_rows(const std::vector<scanline::PixelRow>& rows, const raster::ViewTransform& view,
                  const std::vector<std::uint32_t>& primitive_of_polygon,
                  functional::FrameState& frame) {
  const int w = frame.width();
  for (int y = 0; y < frame.height() && y < static_cast<int>(rows.size()); ++y) {
    const scanline::PixelRow& row = rows[static_cast<std::size_t>(y)];
    for (int x = 0; x < w; ++x) {
      const auto i = static_cast<std::size_t>(x);
      const auto pixel = static_cast<std::uint32_t>(y * w + x);
      frame.fb().add(pixel, row.colour[i]);
      if (row.polygon.empty() || row.polygon[i] < 0) continue;
      const auto polygon = static_cast<std::size_t>(row.polygon[i]);
      Hit hit;
      hit.prim_id = polygon < primitive_of_polygon.size()
                        ? static_cast<std::int32_t>(primitive_of_polygon[polygon])
                        : -1;
      if (!row.depth.empty() && std::isfinite(row.depth[i])) {
        const double z = row.depth[i];
        const double eye = view.near * view.far / (view.far - z * (view.far - view.near));
        const double dx = (x + 0.5 - view.centre_x) * view.pixel;
        const double dy = (y + 0.5 - view.centre_y) * view.pixel;
        hit.surface.t = eye * std::sqrt(1.0 + dx * dx + dy * dy);
      }
      frame.record_primary(pixel, hit.valid(), hit);
    }
  }
}

}  // namespace rtsim::platform::ullner_scanline_tree
