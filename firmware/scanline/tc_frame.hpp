#pragma once
// A scene as the scan-line tree's host loads it (seed 000 §3.1, L969-L1015): convex
// quadrilaterals with a normal at each vertex and one colour (L973). The scene's triangles (the
// rasterization layer's mesh) go in as quadrilaterals whose last vertex repeats the third; the
// colour is the material's colour times its diffuse coefficient.
//
// The literals broadcast with the program (Figs. 3-10, 3-11): the camera's view and perspective
// as one matrix — the ray tracers' pinhole mapping (raster::ViewTransform::camera), so the tree's
// pixels are the traced image's — mapping the visible region to -w <= x, y <= w, 0 <= z <= w
// with w the eye depth, the near plane at the scene's nearest bounding corner (12 bits of z
// after the division, L1266: the camera's hither would leave them all at the far end); and one
// light (Fig. 3-11 has one point source, given by its direction):
// the scene's first light, its direction from the scene's centre, at the ray tracers' ambient
// and light intensity. A scene without lights is lit by the ambient term alone.
#include <cstdint>
#include <vector>

#include "firmware/raster/raster_mesh.hpp"
#include "firmware/raster/view_transform.hpp"
#include "firmware/scanline/tc_program.hpp"
#include "firmware/scene.hpp"
#include "firmware/shading/shade_params.hpp"

namespace rtsim::scanline {

struct TcFrame {
  TcLiterals literals;
  std::vector<TcPolygon> polygons;
  /// The scene primitive each polygon comes from (the id image's value).
  std::vector<std::uint32_t> primitive;
  raster::ViewTransform view;
};

TcFrame tc_frame(const scenes::Scene& scene, const raster::RasterMesh& mesh, int width, int height,
                 const shading::ShadeParams& shade);

}  // namespace rtsim::scanline
