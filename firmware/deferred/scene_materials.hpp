#pragma once
// A scene's materials as a rasterizing machine's deferred shader takes them (seed 004 L63-L65,
// L110): each material's record words (shader id = index + 1, intrinsic colour bytes) and its
// uniform parameters (shading function, kd, ks, shine). Shared by pixelflow and sort-first.
#include <string_view>
#include <vector>

#include "firmware/deferred/deferred_shader.hpp"
#include "firmware/raster/screen_triangle.hpp"
#include "firmware/scene.hpp"

namespace rtsim::deferred {

struct SceneMaterials {
  std::vector<raster::MaterialWord> words;  ///< per material
  std::vector<MaterialUniforms> uniforms;   ///< per material
  bool uses_textures = false;               ///< some material has the pin's or the alley's function
  std::vector<bool> alley;                  ///< per material: the alley's function
};

/// The materials of `scene`; InputError naming `machine` for more materials than the shader
/// id's byte can name (Fig. 8, L110) or a shading function the shaders do not have.
SceneMaterials scene_materials(const scenes::Scene& scene, std::string_view machine);

}  // namespace rtsim::deferred
