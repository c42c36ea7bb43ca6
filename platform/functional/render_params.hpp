#pragma once
// The parameters of the functional renderer and of the shading model, declared in the registry
// so they can be set from a config file or with -p, and listed by `rtsim list params`.
#include <cstdint>
#include <string>

#include "firmware/kernels/wang_arithmetic.hpp"
#include "firmware/shading/shade_params.hpp"
#include "params/registry.hpp"

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
  /// The grid search looks for the closest hit within each subvolume only, as the ray-tracing
  /// array's nodes do (accel::grid_closest_hit_by_subvolume).
  bool grid_by_subvolume = false;
  /// Shell boxes as a PERT's SHELL records hold them (singles rounded outward), so the twin
  /// searches the boxes gaudet-pert's ShellProcessors read out of their packets.
  bool shell_boxes_as_stored = false;
  /// Spheres and triangles as a PERT's PRIM records hold them (centre, radius and vertices in
  /// singles), so the twin tests the primitives gaudet-pert's PrimProcessors read out of their
  /// packets. Vertex normals stay in double: they are the host's, not in the records.
  bool prims_as_stored = false;
  int shell_branching = 4;
  int shell_leaf_size = 8;
  int bezier_iterations = 10;
  int bezier_culler_key_bits = 36;            ///< bezier.culler_key_bits
  kernels::WangArithmetic bezier_arithmetic;  ///< bezier.arithmetic, .fixed_bits, ...
  std::uint64_t scene_seed = 0;               ///< 0: each generator's own default seed
  double view_azimuth_deg = 0.0;    ///< view.azimuth_deg: the eye turned about the vertical
  double view_elevation_deg = 0.0;  ///< view.elevation_deg: the eye raised
  shading::ShadeParams shade;
};

/// Which optional groups of render parameters a functional twin reads. A machine declares only
/// what its twin reads, so setting another (say render.grid.divisions on a machine whose grid is
/// its own) is an error rather than a silent no-op. render.spp, scene.seed, shade.ambient,
/// shade.light_intensity and view.* are read by every twin and always declared.
struct RenderParamUse {
  bool accel = true;           ///< render.accel, render.grid.divisions: the structure's choice
  bool shells = true;          ///< render.shells.*: the box-shell hierarchy's shape
  bool polygon_kernel = true;  ///< render.polygon_kernel
  bool bezier = true;          ///< bezier.iterations (scenes with patches)
  /// shade.max_depth, shade.contribution_threshold: the ray tree's depth and pruning (a machine
  /// that traces no secondary rays, pixelflow, reads neither).
  bool ray_tree = true;
};

/// Declares the render and shading parameters of `use` (all of them by default: the functional
/// renderer's own set).
void declare_render_params(params::ParamRegistry& registry, const RenderParamUse& use = {});
/// Reads the declared ones; an undeclared group keeps RenderSettings' default (the machine that
/// left it out sets that field itself).
RenderSettings read_render_settings(const params::ParamRegistry& registry);
/// scene.seed alone (the scene is generated before any twin is made).
std::uint64_t read_scene_seed(const params::ParamRegistry& registry);

}  // namespace rtsim::functional
