#include "firmware/sortfirst/region_render.hpp"

#include <algorithm>
#include <optional>

#include "firmware/raster/region_samples.hpp"

namespace rtsim::sortfirst {

std::uint64_t shade_tile(const raster::RegionSamples& tile, const raster::ViewTransform& view,
                         const RegionShading& shading, RegionPixels& out) {
  std::vector<Color> colours;
  const deferred::RegionWork w =
      deferred::shade_region(tile, view, shading.setup, shading.tables, colours);
  const raster::RegionSampleGrid& g = tile.at;
  for (int y = 0; y < g.height; ++y)
    for (int x = 0; x < g.width; ++x) {
      const Color& c = colours[static_cast<std::size_t>(y * raster::kRegionWidth + x)];
      out.pixels[static_cast<std::size_t>((g.y0 - out.y0 + y) * out.width + (g.x0 - out.x0 + x))] =
          {raster::colour_byte(c.r), raster::colour_byte(c.g), raster::colour_byte(c.b)};
    }
  return w.lit_pixels;
}

RegionPixels render_region(const raster::RasterMesh& mesh, const raster::ViewTransform& view,
                           const ScreenRegions& regions, int region, const RegionShading& shading) {
  RegionPixels out;
  const int row = region / regions.side, col = region % regions.side;
  out.x0 = regions.x0(col);
  out.y0 = regions.y0(row);
  out.width = regions.x0(col + 1) - out.x0;
  out.height = regions.y0(row + 1) - out.y0;
  out.pixels.assign(static_cast<std::size_t>(out.width) * static_cast<std::size_t>(out.height),
                    PixelBytes{});
  if (out.pixels.empty()) return out;
  const raster::ViewSetup setup = raster::set_up_view(mesh, view, shading.words);
  out.work.triangles = setup.front_facing;
  // One sample a pixel, at the offsets of sample 0 (region_samples.hpp).
  const raster::RegionSampleGrid first =
      raster::RegionSampleGrid::of(raster::RegionGrid{regions.width, regions.height}, 0, 0);
  for (int ty = out.y0; ty < out.y0 + out.height; ty += raster::kRegionHeight)
    for (int tx = out.x0; tx < out.x0 + out.width; tx += raster::kRegionWidth) {
      raster::RegionSampleGrid g = first;
      g.x0 = tx;
      g.y0 = ty;
      g.width = std::min(raster::kRegionWidth, out.x0 + out.width - tx);
      g.height = std::min(raster::kRegionHeight, out.y0 + out.height - ty);
      // One tile buffer a thread, only its used part cleared: a region of a fine partition is a
      // small part of the 128 x 64 buffer.
      thread_local std::optional<raster::RegionSamples> buffer;
      if (!buffer) buffer.emplace(g);
      raster::RegionSamples& tile = *buffer;
      tile.at = g;
      for (int y = 0; y < g.height; ++y)
        std::fill_n(tile.words.begin() + y * raster::kRegionWidth, g.width,
                    raster::background_word());
      for (const auto& t : setup.triangles) {
        if (t.x_max < g.x0 || t.x_min >= g.x0 + g.width || t.y_max < g.y0 ||
            t.y_min >= g.y0 + g.height)
          continue;
        out.work.samples += raster::scan_convert(t, view, tile).covered;
      }
      out.work.shaded += shade_tile(tile, view, shading, out);
    }
  return out;
}

}  // namespace rtsim::sortfirst
