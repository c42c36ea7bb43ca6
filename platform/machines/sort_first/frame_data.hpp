#pragma once
// What a sort-first run is made of before any renderer runs: the scene's primitives as the
// renderers store them (firmware/sortfirst/primitive_record.hpp), the shading every renderer
// holds (the materials, the lights, the textures), the screen's regions and the views of the
// camera path, the last of which is the scene's own camera (so the image, the last frame's,
// equals the functional twin's). The machine and its twin both start from it.
#include <vector>

#include "firmware/deferred/bowling_textures.hpp"
#include "firmware/raster/raster_mesh.hpp"
#include "firmware/raster/view_transform.hpp"
#include "firmware/scene.hpp"
#include "firmware/shading/shade_params.hpp"
#include "firmware/sortfirst/region_render.hpp"
#include "firmware/sortfirst/screen_regions.hpp"
#include "platform/functional/frame_state.hpp"

namespace rtsim::platform::sort_first {

/// The most triangles the renderers are given memory for (each held once, and again as a copy
/// in each further region it covers): a bound on memory, not the machine's.
inline constexpr double kMaxTriangles = 1'000'000;

struct FrameData {
  raster::RasterMesh mesh;  ///< as stored: single-precision records unpacked
  deferred::BowlingTextures textures;
  sortfirst::RegionShading shading;
  sortfirst::ScreenRegions regions;
};

/// Builds it (shading.tables points into the result's textures: keep it where it is built).
/// Throws InputError for a scene the machine cannot hold.
void make_frame_data(FrameData& out, const scenes::Scene& scene, const raster::MeshSettings& mesh,
                     const shading::ShadeParams& shade, int side, int width, int height);

/// A run's camera path (`camera.*`), built backwards from its last frame, which is the scene's
/// own view.
struct CameraPath {
  /// Spin: the view turned `spin` degrees a frame about its vertical axis through the point
  /// looked at (seed 004 L572: PLB spins the model 4.5 degrees an iteration about a vertical
  /// axis through its centre). Fly: sequences of `sequence` frames, in each of which the eye
  /// closes in on the point looked at by `dolly` of its distance a frame while it turns `spin`
  /// degrees a frame, with an abrupt reset to the sequence's start between them (the Sierra
  /// path's "zooms, rotations, and translations, with an abrupt reset between each sequence",
  /// L588-L589).
  bool fly = false;
  double spin = 0.0;
  double dolly = 0.0;
  int sequence = 1;
};

/// The view of frame `f` of `frames` on `path`.
raster::ViewTransform frame_view(const scenes::Scene& scene, const raster::RasterMesh& mesh,
                                 int width, int height, int f, int frames, const CameraPath& path);

/// Region `r`'s pixels into the frame (the frame buffer's and the twin's one way of doing it).
void paint_region(functional::FrameState& frame, const sortfirst::RegionPixels& p);

/// The functional twin's frame: every region rendered from the primitives whose box covers it.
void render_frame(const FrameData& data, const raster::ViewTransform& view,
                  functional::FrameState& frame);

}  // namespace rtsim::platform::sort_first
