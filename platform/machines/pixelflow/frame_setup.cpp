#include "platform/machines/pixelflow/frame_setup.hpp"

#include <string>

#include "common/input_error.hpp"
#include "firmware/deferred/scene_materials.hpp"

namespace rtsim::platform::pixelflow {

FrameSetup make_frame_setup(const scenes::Scene& scene, const FrameSettings& settings, int width,
                            int height, int spp) {
  FrameSetup f;
  f.width = width;
  f.height = height;
  f.spp = spp;
  const deferred::SceneMaterials materials = deferred::scene_materials(scene, "pixelflow");
  // The tessellation's size, bounded before anything is allocated: a scene of many spheres at
  // a fine mesh.sphere_segments would otherwise take all the memory there is.
  const double estimate = raster::estimated_triangles(scene, settings.mesh);
  if (estimate > kMaxTriangles)
    throw InputError(
        scene.name, 0,
        "pixelflow: tessellated at mesh.sphere_segments = " +
            std::to_string(settings.mesh.sphere_segments) +
            ", mesh.cone_segments = " + std::to_string(settings.mesh.cone_segments) +
            " and mesh.patch_segments = " + std::to_string(settings.mesh.patch_segments) +
            " the scene would be about " + std::to_string(static_cast<long long>(estimate)) +
            " triangles, more than the " + std::to_string(kMaxTriangles) +
            " the rasterizers are given memory for; lower them");
  f.mesh = raster::build_raster_mesh(scene, settings.mesh);
  f.shading.lights = scene.lights;
  f.shading.shade = settings.shade;
  f.shading.background = scene.background;
  f.shading.shadow_bias_texels = settings.shadow_bias_texels;
  f.shading.bump_scale = settings.bump_scale;
  f.words = materials.words;
  f.shading.materials = materials.uniforms;
  f.uses_textures = materials.uses_textures;
  std::vector<bool> not_alley(scene.materials.size(), true);
  bool any_alley = false;
  for (std::size_t m = 0; m < materials.alley.size(); ++m)
    if (materials.alley[m]) {
      not_alley[m] = false;
      any_alley = true;
    }
  if (f.uses_textures) f.textures = deferred::make_bowling_textures();
  f.camera = raster::ViewTransform::camera(scene.camera, width, height, f.mesh.bounds);
  // A shadow map covers what the camera sees: aimed from the light at the box of the vertices
  // in the camera's view (a triangle with a vertex there is on the screen), so its texels are
  // spent where they are looked up; the whole scene if no vertex is in view.
  Bounds seen;
  for (const auto& t : f.mesh.triangles)
    for (const auto& v : t.v) {
      const Vec3 e = f.camera.to_eye(v.position);
      if (!(e.z > f.camera.near)) continue;
      const double sx = f.camera.screen_x(e), sy = f.camera.screen_y(e);
      if (sx >= -0.1 * width && sx <= 1.1 * width && sy >= -0.1 * height && sy <= 1.1 * height)
        seen.extend(v.position);
    }
  if (seen.empty()) seen = f.mesh.bounds;
  for (const auto& light : scene.lights)
    f.shadow_views.push_back(
        raster::ViewTransform::enclosing(light.position, seen, f.mesh.bounds, settings.map_size));
  if (any_alley) {
    // The reflector's plane: its first triangle's, facing the camera. A reflector the camera sees
    // from behind reflects nothing it could show.
    for (const auto& t : f.mesh.triangles) {
      if (not_alley[t.material]) continue;
      Vec3 n = t.face_normal;
      const Vec3 p = t.v[0].position;
      if (glm::dot(n, f.camera.origin - p) < 0.0) n = -n;
      if (!(glm::dot(n, f.camera.origin - p) > 0.0)) break;
      MirrorPass mirror;
      mirror.plane = {p, n};
      mirror.view = f.camera.mirrored(p, n, settings.map_size, f.mesh.bounds);
      mirror.include = not_alley;
      f.mirror = std::move(mirror);
      break;
    }
  }
  return f;
}

}  // namespace rtsim::platform::pixelflow
