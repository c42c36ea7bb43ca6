#include "firmware/deferred/scene_materials.hpp"

#include <string>

#include "common/input_error.hpp"
#include "common/suggest.hpp"

namespace rtsim::deferred {

namespace {

/// The shading function material `m` names; InputError for a name no function has.
ShadingFunction function_of(const scenes::Scene& scene, std::uint32_t m, std::string_view machine) {
  const std::string& name = raster::surface_shading(scene, m).shader;
  if (const auto f = shading_function_named(name)) return *f;
  const std::vector<std::string_view> names(kShadingFunctionNames.begin(),
                                            kShadingFunctionNames.end());
  throw InputError(scene.name, 0,
                   std::string(machine) + ": material " + std::to_string(m) +
                       " asks for shading function '" + name + "', which its shaders do not have" +
                       did_you_mean(name, names));
}

}  // namespace

SceneMaterials scene_materials(const scenes::Scene& scene, std::string_view machine) {
  // Fig. 8's shader id is one byte and 0 is the background (appearance.hpp).
  if (scene.materials.size() > 255)
    throw InputError(scene.name, 0,
                     std::string(machine) + ": the scene has " +
                         std::to_string(scene.materials.size()) +
                         " materials; a sample's shader id is one byte (seed 004 Fig. 8, L110), "
                         "so at most 255 can be told apart");
  SceneMaterials out;
  for (std::uint32_t m = 0; m < scene.materials.size(); ++m) {
    const auto& mat = scene.materials[m];
    const ShadingFunction fn = function_of(scene, m, machine);
    out.words.push_back({static_cast<std::uint8_t>(m + 1),
                         {raster::colour_byte(mat.color.r), raster::colour_byte(mat.color.g),
                          raster::colour_byte(mat.color.b)}});
    out.uniforms.push_back({fn, mat.kd, mat.ks, mat.shine});
    if (fn == ShadingFunction::Pin || fn == ShadingFunction::Alley) out.uses_textures = true;
    out.alley.push_back(fn == ShadingFunction::Alley);
  }
  return out;
}

}  // namespace rtsim::deferred
