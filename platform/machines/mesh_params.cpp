#include "platform/machines/mesh_params.hpp"

namespace rtsim::platform {

namespace {
const modules::IntParam kSphereSegments(
    {.name = "mesh.sphere_segments",
     .default_value = "24",
     .min = "3",
     .max = "1024",
     .description = "segments round a sphere (and half as many rings) when it is tessellated "
                    "into triangles",
     .source = "assumption: the seeds' rasterizing machines take polygons (seed 004 L93, seed "
               "000 L973); 24 keeps an NFF sphere's outline within a pixel of round at a few "
               "hundred pixels across"});
const modules::IntParam kConeSegments(
    {.name = "mesh.cone_segments",
     .default_value = "24",
     .min = "3",
     .max = "1024",
     .description = "segments round a cone or cylinder when it is tessellated",
     .source = "assumption: as mesh.sphere_segments"});
const modules::IntParam kPatchSegments(
    {.name = "mesh.patch_segments",
     .default_value = "8",
     .min = "1",
     .max = "256",
     .description = "quads a side of a Bezier patch's tessellation (each two triangles)",
     .source = "assumption: the teapot's 32 patches become 4096 triangles, as many as the "
               "bowling frame's pins"});
}  // namespace

void declare_mesh_params(const modules::ParamDecls& image) {
  for (const auto* p : {&kSphereSegments, &kConeSegments, &kPatchSegments}) image.add(*p);
}

raster::MeshSettings read_mesh_params(const params::ParamRegistry& registry) {
  const modules::ModuleParams p(registry, "");
  raster::MeshSettings s;
  s.sphere_segments = static_cast<int>(p.get(kSphereSegments));
  s.cone_segments = static_cast<int>(p.get(kConeSegments));
  s.patch_segments = static_cast<int>(p.get(kPatchSegments));
  return s;
}

}  // namespace rtsim::platform
