#include "platform/machines/sort_first/frame_data.hpp"

#include <algorithm>
#include <string>

#include "common/input_error.hpp"
#include "firmware/deferred/scene_materials.hpp"
#include "firmware/sortfirst/primitive_record.hpp"
#include "platform/machines/camera_turn.hpp"

namespace rtsim::platform::sort_first {

void make_frame_data(FrameData& out, const scenes::Scene& scene, const raster::MeshSettings& mesh,
                     const shading::ShadeParams& shade, int side, int width, int height) {
  const deferred::SceneMaterials materials = deferred::scene_materials(scene, "sort-first");
  const double estimate = raster::estimated_triangles(scene, mesh);
  if (estimate > kMaxTriangles)
    throw InputError(
        scene.name, 0,
        "sort-first: the scene would be about " + std::to_string(static_cast<long long>(estimate)) +
            " triangles, more than the " + std::to_string(static_cast<long long>(kMaxTriangles)) +
            " the renderers are given memory for; lower mesh.*");
  out.mesh = sortfirst::stored_mesh(raster::build_raster_mesh(scene, mesh), materials.words.size());
  if (materials.uses_textures) out.textures = deferred::make_bowling_textures();
  out.shading.words = materials.words;
  out.shading.setup.materials = materials.uniforms;
  out.shading.setup.lights = scene.lights;
  out.shading.setup.shade = shade;
  out.shading.setup.background = scene.background;
  out.shading.tables = {};
  out.shading.tables.textures = materials.uses_textures ? &out.textures : nullptr;
  // A light without a shadow map lights everything (deferred_shader.hpp).
  out.shading.tables.shadow.assign(scene.lights.size(), nullptr);
  out.regions = {side, width, height};
}

raster::ViewTransform frame_view(const scenes::Scene& scene, const raster::RasterMesh& mesh,
                                 int width, int height, int f, int frames, const CameraPath& path) {
  // Frames before the last (spin), or before the end of the frame's sequence (fly).
  const int before = path.fly ? (frames - 1 - f) % std::max(1, path.sequence) : frames - 1 - f;
  scenes::Camera c = scene.camera;
  if (path.fly) c.from = c.at + (c.from - c.at) * (1.0 + path.dolly * before);
  c = turned_about_up(c, -path.spin * before);
  return raster::ViewTransform::camera(c, width, height, mesh.bounds);
}

void paint_region(functional::FrameState& frame, const sortfirst::RegionPixels& p) {
  for (int y = 0; y < p.height; ++y)
    for (int x = 0; x < p.width; ++x) {
      const auto& c = p.pixels[static_cast<std::size_t>(y * p.width + x)];
      frame.fb().add(static_cast<std::uint32_t>((p.y0 + y) * frame.width() + p.x0 + x),
                     Color(c[0], c[1], c[2]) / 255.0);
    }
}

void render_frame(const FrameData& data, const raster::ViewTransform& view,
                  functional::FrameState& frame) {
  const int n = data.regions.count();
  std::vector<raster::RasterMesh> bins(static_cast<std::size_t>(n));
  for (const auto& t : data.mesh.triangles) {
    const sortfirst::RegionRange range = sortfirst::classify(t, view, data.regions);
    for (int r = range.r0; range.on_screen && r <= range.r1; ++r)
      for (int c = range.c0; c <= range.c1; ++c)
        bins[static_cast<std::size_t>(data.regions.index(r, c))].triangles.push_back(t);
  }
  for (int k = 0; k < n; ++k)
    paint_region(frame, sortfirst::render_region(bins[static_cast<std::size_t>(k)], view,
                                                 data.regions, k, data.shading));
}

}  // namespace rtsim::platform::sort_first
