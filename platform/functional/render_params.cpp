#include "platform/functional/render_params.hpp"

namespace rtsim::functional {

using params::ParamKind;

void declare_render_params(params::ParamRegistry& r, const RenderParamUse& use) {
  r.declare({.name = "render.spp",
             .kind = ParamKind::kInt,
             .default_value = "1",
             .min = "1",
             .max = "4096",
             .unit = "samples",
             .description = "Samples (primary rays) per pixel; sample 0 is the pixel centre",
             .source = "seed 000 L590: the machines' figures assume one vision ray per pixel"});
  if (use.accel) {
    r.declare({.name = "render.accel",
               .kind = ParamKind::kString,
               .default_value = "shells",
               .allowed = {"grid", "shells", "none"},
               .description = "Acceleration structure of the functional renderer: Ullner's uniform "
                              "grid with the corrected 3-D DDA, Gaudet's box-shell hierarchy, or "
                              "none (every ray tests every primitive)",
               .source = "assumption: measured fastest on most shared scenes (docs/benchmarks.md); "
                         "a uniform grid suffers from the SPD floors' large extent"});
  }
  if (use.polygon_kernel) {
    r.declare({.name = "render.polygon_kernel",
               .kind = ParamKind::kString,
               .default_value = "triangle",
               .allowed = {"triangle", "ullner-quad"},
               .description = "How polygons are intersected: ear-clipped triangles with a "
                              "watertight test, or Ullner's convex quadrilaterals (20 parameters, "
                              "seed 000 §2.2)",
               .source = "assumption: triangles are the cheaper exact test in software"});
  }
  if (use.accel) {
    r.declare({.name = "render.grid.divisions",
               .kind = ParamKind::kInt,
               .default_value = "0",
               .min = "0",
               .max = "512",
               .unit = "per axis",
               .description = "Subvolumes per axis of the grid; 0 chooses from the primitive count "
                              "(at most 512: 512^3 subvolumes is the grid's limit, kMaxGridCells "
                              "= 2^27)",
               .source = "seed 000 L648-L654: Ullner's time model gives n_s = 1.10 cbrt(n_p) "
                         "(docs/parameters.md)"});
  }
  if (use.shells) {
    r.declare({.name = "render.shells.branching",
               .kind = ParamKind::kInt,
               .default_value = "4",
               .min = "2",
               .max = "8",
               .unit = "children",
               .description = "Children per parent shell when the scene has no clusters",
               .source = "seed 001 L970: Gaudet's test scenes use 2, 4 and 8"});
  }
  if (use.shells) {
    r.declare({.name = "render.shells.leaf_size",
               .kind = ParamKind::kInt,
               .default_value = "8",
               .min = "1",
               .max = "64",
               .unit = "primitives",
               .description = "Most primitives per leaf shell when the scene has no clusters",
               .source = "seed 001 L970: Gaudet's npp scenes hold 4 to 20 per leaf shell"});
  }
  if (use.bezier) {
    r.declare({.name = "bezier.iterations",
               .kind = ParamKind::kInt,
               .default_value = "10",
               .min = "1",
               .max = "30",
               .unit = "stages",
               .description = "Subdivision loop stages of Wang's ray/patch algorithm",
               .source = "seed 002 L284: the hardware has 10 loop stages"});
  }
  r.declare({.name = "scene.seed",
             .kind = ParamKind::kInt,
             .default_value = "0",
             .min = "0",
             .description = "Seed of the built-in scene generators; 0 keeps each generator's own",
             .source = "assumption: generators are reproducible by default"});
  r.declare({.name = "shade.ambient",
             .kind = ParamKind::kDouble,
             .default_value = "0.1",
             .min = "0",
             .max = "1",
             .description = "Ambient intensity I_a of the Phong term R*I_a",
             .source = "seed 000 L414 (form); value an assumption: NFF has no ambient term"});
  r.declare({.name = "shade.max_depth",
             .kind = ParamKind::kInt,
             .default_value = "5",
             .min = "0",
             .max = "64",
             .unit = "generations",
             .description = "Depth limit of the ray tree (reflected/refracted generations)",
             .source = "assumption: deeper trees change no 8-bit pixel in the SPD scenes"});
  r.declare({.name = "shade.contribution_threshold",
             .kind = ParamKind::kDouble,
             .default_value = "0.00392156862745098",
             .min = "0",
             .max = "1",
             .description = "Hall's adaptive tree depth: reflected/refracted rays whose "
                            "contribution factor is below this are not spawned",
             .source = "seed 001 §4.3.5 (no value given); assumption: 1/255, one 8-bit step"});
  r.declare({.name = "shade.light_intensity",
             .kind = ParamKind::kDouble,
             .default_value = "0",
             .min = "0",
             .description = "Intensity of each point light; 0 = 1/sqrt(number of lights)",
             .source = "assumption: keeps scenes with many lights from burning out"});
}

RenderSettings read_render_settings(const params::ParamRegistry& r) {
  RenderSettings s;
  s.spp = static_cast<int>(r.get_int("render.spp"));
  if (r.contains("render.accel")) {
    const std::string& accel = r.get_string("render.accel");
    s.accel = accel == "shells" ? AccelKind::Shells
              : accel == "none" ? AccelKind::None
                                : AccelKind::Grid;
    s.grid_divisions = static_cast<int>(r.get_int("render.grid.divisions"));
  }
  if (r.contains("render.polygon_kernel"))
    s.polygon_kernel = r.get_string("render.polygon_kernel") == "ullner-quad"
                           ? PolygonKernel::UllnerQuad
                           : PolygonKernel::Triangle;
  if (r.contains("render.shells.branching")) {
    s.shell_branching = static_cast<int>(r.get_int("render.shells.branching"));
    s.shell_leaf_size = static_cast<int>(r.get_int("render.shells.leaf_size"));
  }
  if (r.contains("bezier.iterations"))
    s.bezier_iterations = static_cast<int>(r.get_int("bezier.iterations"));
  s.scene_seed = static_cast<std::uint64_t>(r.get_int("scene.seed"));
  s.shade.ambient = r.get_double("shade.ambient");
  s.shade.max_depth = static_cast<int>(r.get_int("shade.max_depth"));
  s.shade.contribution_threshold = r.get_double("shade.contribution_threshold");
  s.shade.light_intensity = r.get_double("shade.light_intensity");
  return s;
}

}  // namespace rtsim::functional
