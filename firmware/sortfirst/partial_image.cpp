#include "firmware/sortfirst/partial_image.hpp"

namespace rtsim::sortfirst {

PartialImage render_partial(const raster::RasterMesh& mesh, const raster::ViewTransform& view,
                            int width, int height, const std::vector<raster::MaterialWord>& words) {
  PartialImage out;
  const raster::ViewSetup setup = raster::set_up_view(mesh, view, words);
  out.work.triangles = setup.front_facing;
  const raster::RegionGrid grid{width, height};
  for (int t = 0; t < grid.count(); ++t) {
    auto tile = std::make_shared<raster::RegionSamples>(raster::RegionSampleGrid::of(grid, t, 0));
    const raster::RegionSampleGrid& g = tile->at;
    for (const auto& tri : setup.triangles) {
      if (tri.x_max < g.x0 || tri.x_min >= g.x0 + g.width || tri.y_max < g.y0 ||
          tri.y_min >= g.y0 + g.height)
        continue;
      out.work.samples += raster::scan_convert(tri, view, *tile).covered;
    }
    for (int y = 0; y < g.height; ++y)
      for (int x = 0; x < g.width; ++x)
        out.work.shaded += raster::depth_word(tile->word(x, y)) != raster::kBackgroundDepth;
    out.tiles.push_back(std::move(tile));
  }
  return out;
}

}  // namespace rtsim::sortfirst
