#pragma once
// The tessellation parameters of the machines that rasterize (pixelflow, ullner-scanline-tree):
// how spheres, cones and Bezier patches become the triangles their primitives are
// (firmware/raster/raster_mesh.hpp). The image depends on them.
#include "firmware/raster/raster_mesh.hpp"
#include "modules/module_params.hpp"
#include "params/registry.hpp"

namespace rtsim::platform {

/// Declares `mesh.*` (marked as parameters the image depends on) under `image`.
void declare_mesh_params(const modules::ParamDecls& image);
raster::MeshSettings read_mesh_params(const params::ParamRegistry& registry);

}  // namespace rtsim::platform
