#pragma once
// The parameters of the functional renderer and of the shading model, declared in the registry
// so they can be set from a config file or with -p, and listed by `rtsim list params`.
#include <string>

#include "firmware/shading/shade_params.hpp"
#include "platform/params/registry.hpp"

namespace rtsim::functional {

/// Acceleration structure used by the functional renderer.
enum class AccelKind { Grid, Shells, None };

/// Kernel the functional renderer uses for NFF polygons.
enum class PolygonKernel { Triangle, UllnerQuad };

struct RenderSettings {
  int spp = 1;
  AccelKind accel = AccelKind::Shells;
  PolygonKernel polygon_kernel = PolygonKernel::Triangle;
  int grid_divisions = 0;       ///< per axis; 0 = chosen from the primitive count
  bool dda_as_printed = false;  ///< Appendix B exactly as printed (machines' fidelity option)
  int shell_branching = 4;
  int shell_leaf_size = 8;
  int bezier_iterations = 10;
  std::uint64_t scene_seed = 0;  ///< 0: each generator's own default seed
  shading::ShadeParams shade;
};

void declare_render_params(params::ParamRegistry& registry);
RenderSettings read_render_settings(const params::ParamRegistry& registry);

}  // namespace rtsim::functional
