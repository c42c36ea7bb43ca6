#include "platform/machines/pixelflow/functional_passes.hpp"

#include "platform/machines/pixelflow/frame_buffer_node.hpp"

namespace rtsim::platform::pixelflow {

std::vector<std::vector<std::uint32_t>> bin_by_region(const raster::ViewSetup& setup,
                                                      const raster::RegionGrid& grid) {
  std::vector<std::vector<std::uint32_t>> bins(static_cast<std::size_t>(grid.count()));
  const int cols = grid.columns();
  for (std::uint32_t i = 0; i < setup.triangles.size(); ++i) {
    const auto& t = setup.triangles[i];
    const int c0 = t.x_min / raster::kRegionWidth, c1 = t.x_max / raster::kRegionWidth;
    const int r0 = t.y_min / raster::kRegionHeight, r1 = t.y_max / raster::kRegionHeight;
    for (int r = r0; r <= r1; ++r)
      for (int c = c0; c <= c1; ++c) bins[static_cast<std::size_t>(r * cols + c)].push_back(i);
  }
  return bins;
}

deferred::ShadingTables tables_of(const FrameSetup& f, const FrameMaps& maps,
                                  bool without_reflection) {
  deferred::ShadingTables t;
  t.textures = f.uses_textures ? &f.textures : nullptr;
  for (const auto& m : maps.shadow) t.shadow.push_back(&m);
  if (!without_reflection && maps.reflection) t.reflection = &*maps.reflection;
  return t;
}

FrameMaps render_maps(const FrameSetup& f) {
  FrameMaps maps;
  // Shadow maps: depth only, from each light (L118-L120).
  for (const auto& view : f.shadow_views) {
    raster::DepthMap map(view);
    const raster::ViewSetup setup = raster::set_up_view(f.mesh, view, f.words);
    const raster::RegionGrid grid{view.width, view.height};
    const auto bins = bin_by_region(setup, grid);
    for (int r = 0; r < grid.count(); ++r) {
      raster::RegionDepths region(raster::RegionSampleGrid::of(grid, r, 0));
      for (const std::uint32_t i : bins[static_cast<std::size_t>(r)])
        raster::scan_depth(setup.triangles[i], view, region);
      map.store(region);
    }
    maps.shadow.push_back(std::move(map));
  }
  // The reflection map: the mirrored view shaded with the shadow maps, one sample a texel (L128).
  if (f.mirror) {
    const raster::ViewTransform& view = f.mirror->view;
    raster::ColourMap map(view, f.shading.background);
    const raster::ViewSetup setup =
        raster::set_up_view(f.mesh, view, f.words, f.mirror->include, f.mirror->plane);
    const raster::RegionGrid grid{view.width, view.height};
    const auto bins = bin_by_region(setup, grid);
    const deferred::ShadingTables tables = tables_of(f, maps, true);
    std::vector<Color> colours;
    for (int r = 0; r < grid.count(); ++r) {
      raster::RegionSamples region(raster::RegionSampleGrid::of(grid, r, 0));
      for (const std::uint32_t i : bins[static_cast<std::size_t>(r)])
        raster::scan_convert(setup.triangles[i], view, region);
      deferred::shade_region(region, view, f.shading, tables, colours);
      for (int y = 0; y < region.at.height; ++y)
        for (int x = 0; x < region.at.width; ++x)
          map.set(region.at.x0 + x, region.at.y0 + y,
                  colours[static_cast<std::size_t>(y * raster::kRegionWidth + x)]);
    }
    maps.reflection = std::move(map);
  }
  return maps;
}

void render_camera(const FrameSetup& f, const FrameMaps& maps, functional::FrameState& frame) {
  const raster::ViewSetup setup = raster::set_up_view(f.mesh, f.camera, f.words);
  const raster::RegionGrid grid{f.width, f.height};
  const auto bins = bin_by_region(setup, grid);
  const deferred::ShadingTables tables = tables_of(f, maps);
  std::vector<Color> colours;
  for (int r = 0; r < grid.count(); ++r)
    for (int s = 0; s < f.spp; ++s) {
      raster::RegionSamples region(raster::RegionSampleGrid::of(grid, r, s));
      for (const std::uint32_t i : bins[static_cast<std::size_t>(r)])
        raster::scan_convert(setup.triangles[i], f.camera, region);
      deferred::shade_region(region, f.camera, f.shading, tables, colours);
      add_into(frame, ShadedRegion{0, 0, region.at, colour_bytes(colours)});
    }
}

}  // namespace rtsim::platform::pixelflow
