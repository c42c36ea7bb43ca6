#pragma once
// PixelFlow's frame with no timing: the passes the machine runs (seed 004 L114-L158) — a shadow
// map from each light, the reflection map, the camera's image at `spp` samples a pixel — each
// rasterized region by region and z-composited, the maps stored as tables and the images shaded
// by deferred shading. It is the machine's functional twin (`rtsim render --machine pixelflow`)
// and the pieces the machine's nodes share with it.
#include <cstdint>
#include <optional>
#include <vector>

#include "firmware/raster/region_grid.hpp"
#include "firmware/raster/table_maps.hpp"
#include "platform/functional/frame_state.hpp"
#include "platform/machines/pixelflow/frame_setup.hpp"

namespace rtsim::platform::pixelflow {

/// For each region of `grid`, the indices into `setup.triangles` of the triangles whose bounding
/// box meets it, in order: a rasterizer sets up a triangle once for every region it meets (the
/// duplicates at region boundaries, L132).
std::vector<std::vector<std::uint32_t>> bin_by_region(const raster::ViewSetup& setup,
                                                      const raster::RegionGrid& grid);

/// The maps of a frame, as every shading node's table memory holds them.
struct FrameMaps {
  std::vector<raster::DepthMap> shadow;  ///< one per light
  std::optional<raster::ColourMap> reflection;
};

/// The shading nodes' tables for shading with `maps` (the textures, the shadow maps; the
/// reflection map unless `without_reflection`).
deferred::ShadingTables tables_of(const FrameSetup& f, const FrameMaps& maps,
                                  bool without_reflection = false);

/// The shadow maps and the reflection map, rendered as the machine's map passes do.
FrameMaps render_maps(const FrameSetup& f);

/// The camera pass into `frame`'s frame buffer: every region, every sample.
void render_camera(const FrameSetup& f, const FrameMaps& maps, functional::FrameState& frame);

}  // namespace rtsim::platform::pixelflow
