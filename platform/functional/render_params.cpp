#include "platform/functional/render_params.hpp"

#include "common/input_error.hpp"
#include "modules/module_params.hpp"

namespace rtsim::functional {

namespace {

// The functional renderer's and the shading model's parameters, each named once.
const modules::IntParam kSpp(
    {.name = "render.spp",
     .default_value = "1",
     .min = "1",
     .max = "4096",
     .unit = "samples",
     .description = "Samples (primary rays) per pixel; sample 0 is the pixel centre",
     .source = "seed 000 L590: the machines' figures assume one vision ray per pixel"});
const modules::ChoiceParam kAccel(
    {.name = "render.accel",
     .default_value = "shells",
     .allowed = {"grid", "shells", "none"},
     .description = "Acceleration structure of the functional renderer: Ullner's uniform grid "
                    "with the corrected 3-D DDA, Gaudet's box-shell hierarchy, or none (every ray "
                    "tests every primitive)",
     .source = "assumption: measured fastest on most shared scenes (docs/benchmarks.md); a "
               "uniform grid suffers from the SPD floors' large extent"});
const modules::ChoiceParam kPolygonKernel(
    {.name = "render.polygon_kernel",
     .default_value = "triangle",
     .allowed = {"triangle", "ullner-quad"},
     .description = "How polygons are intersected: ear-clipped triangles with a watertight test, "
                    "or Ullner's convex quadrilaterals (20 parameters, seed 000 §2.2)",
     .source = "assumption: triangles are the cheaper exact test in software"});
const modules::IntParam kGridDivisions(
    {.name = "render.grid.divisions",
     .default_value = "0",
     .min = "0",
     .max = "512",
     .unit = "per axis",
     .description = "Subvolumes per axis of the grid; 0 chooses from the primitive count (at most "
                    "512: 512^3 subvolumes is the grid's limit, kMaxGridCells = 2^27)",
     .source = "seed 000 L648-L654: Ullner's time model gives n_s = 1.10 cbrt(n_p) "
               "(docs/parameters.md)"});
const modules::IntParam kShellBranching(
    {.name = "render.shells.branching",
     .default_value = "4",
     .min = "2",
     .max = "8",
     .unit = "children",
     .description = "Children per parent shell when the scene has no clusters",
     .source = "seed 001 L970: Gaudet's test scenes use 2, 4 and 8"});
const modules::IntParam kShellLeafSize(
    {.name = "render.shells.leaf_size",
     .default_value = "8",
     .min = "1",
     .max = "64",
     .unit = "primitives",
     .description = "Most primitives per leaf shell when the scene has no clusters",
     .source = "seed 001 L970: Gaudet's npp scenes hold 4 to 20 per leaf shell"});
const modules::IntParam kBezierIterations(
    {.name = "bezier.iterations",
     .default_value = "10",
     .min = "1",
     .max = "30",
     .unit = "stages",
     .description = "Subdivision loop stages of Wang's ray/patch algorithm",
     .source = "seed 002 L284: the hardware has 10 loop stages"});
const modules::IntParam kBezierCullerKeyBits(
    {.name = "bezier.culler_key_bits",
     .default_value = "36",
     .min = "5",
     .max = "36",
     .unit = "bits",
     .description = "Bits of the Culler's sort keys: a single's 32 and the 4-bit patch tag (36); "
                    "fewer keep only the distance's top bits, so near subpatches tie and the tag "
                    "decides (12: the prototype's scaled-down Culler). The twin culls alike",
     .source = "seed 002 L304-L306 (36-bit keys), L316 (the 12-bit prototype)"});
const modules::ChoiceParam kBezierArithmetic(
    {.name = "bezier.arithmetic",
     .default_value = "float32",
     .allowed = {"float32", "float64", "fixed"},
     .description = "Arithmetic of Wang's pipeline: the DSPs' single precision, double, or fixed "
                    "point (words of bezier.fixed_bits bits, bezier.fixed_integer_bits above the "
                    "point: every word a block writes rounded and saturated). The jobs' words "
                    "stay singles; the twin computes alike",
     .source = "seed 002 L296 (the TMS320C6701's single precision); double and fixed point are "
               "what-ifs"});
const modules::IntParam kBezierFixedBits(
    {.name = "bezier.fixed_bits",
     .default_value = "24",
     .min = "8",
     .max = "53",
     .unit = "bits",
     .description = "Width of a fixed-point word (bezier.arithmetic = fixed), the sign included",
     .source = "what-if: the paper's DSPs are floating point; 53 bits is all a double holds"});
const modules::IntParam kBezierFixedIntegerBits(
    {.name = "bezier.fixed_integer_bits",
     .default_value = "8",
     .min = "2",
     .max = "32",
     .unit = "bits",
     .description = "Bits of a fixed-point word above the binary point, the sign included: "
                    "words saturate at +-2^(bits - 1) (8: +-128, room for a scene of tens of "
                    "units and the distances to it)",
     .source = "what-if (the teapot spans about 6 units, its camera about 20 away)"});
const modules::IntParam kSceneSeed(
    {.name = "scene.seed",
     .default_value = "0",
     .min = "0",
     .description = "Seed of the built-in scene generators; 0 keeps each generator's own",
     .source = "study setting: generators are reproducible by default"});
const modules::RealParam kAmbient(
    {.name = "shade.ambient",
     .default_value = "0.1",
     .min = "0",
     .max = "1",
     .description = "Ambient intensity I_a of the Phong term R*I_a",
     .source = "seed 000 L414 (form); value an assumption: NFF has no ambient term"});
const modules::IntParam kMaxDepth(
    {.name = "shade.max_depth",
     .default_value = "5",
     .min = "0",
     .max = "64",
     .unit = "generations",
     .description = "Depth limit of the ray tree (reflected/refracted generations)",
     .source = "assumption: deeper trees change no 8-bit pixel in the SPD scenes"});
const modules::RealParam kContributionThreshold(
    {.name = "shade.contribution_threshold",
     .default_value = "0.00392156862745098",
     .min = "0",
     .max = "1",
     .description = "Hall's adaptive tree depth: reflected/refracted rays whose contribution "
                    "factor is below this are not spawned",
     .source = "seed 001 §4.3.5 (no value given); assumption: 1/255, one 8-bit step"});
const modules::RealParam kLightIntensity(
    {.name = "shade.light_intensity",
     .default_value = "0",
     .min = "0",
     .description = "Intensity of each point light; 0 = 1/sqrt(number of lights)",
     .source = "assumption: keeps scenes with many lights from burning out"});

const modules::RealParam kViewAzimuth(
    {.name = "view.azimuth_deg",
     .default_value = "0",
     .min = "-360",
     .max = "360",
     .unit = "degrees",
     .description = "Turns the eye about the vertical (the camera's up) through the point it "
                    "looks at, counter-clockwise seen from above; lights stay",
     .source = "a study setting (other views of a scene, or of a .bpt file's automatic one)"});
const modules::RealParam kViewElevation(
    {.name = "view.elevation_deg",
     .default_value = "0",
     .min = "-89",
     .max = "89",
     .unit = "degrees",
     .description = "Raises the eye toward the camera's up (negative: lowers it) about the point "
                    "it looks at, its elevation kept within 89 degrees of the horizontal",
     .source = "a study setting (other views of a scene)"});

}  // namespace

void declare_render_params(params::ParamRegistry& r, const RenderParamUse& use) {
  // Every one is the functional renderer's: the image depends on each.
  const modules::ParamDecls top = modules::ParamDecls(r, "", false).affecting_image();
  top.add(kSpp);
  if (use.accel) top.add(kAccel);
  if (use.polygon_kernel) top.add(kPolygonKernel);
  if (use.accel) top.add(kGridDivisions);
  if (use.shells) {
    top.add(kShellBranching);
    top.add(kShellLeafSize);
  }
  if (use.bezier) {
    top.add(kBezierIterations);
    top.add(kBezierCullerKeyBits);
    top.add(kBezierArithmetic);
    top.add(kBezierFixedBits);
    top.add(kBezierFixedIntegerBits);
  }
  top.add(kSceneSeed);
  top.add(kAmbient);
  if (use.ray_tree) {
    top.add(kMaxDepth);
    top.add(kContributionThreshold);
  }
  top.add(kLightIntensity);
  top.add(kViewAzimuth);
  top.add(kViewElevation);
}

std::uint64_t read_scene_seed(const params::ParamRegistry& r) {
  return static_cast<std::uint64_t>(modules::ModuleParams(r, "").get(kSceneSeed));
}

RenderSettings read_render_settings(const params::ParamRegistry& r) {
  const modules::ModuleParams p(r, "");
  RenderSettings s;
  s.spp = static_cast<int>(p.get(kSpp));
  if (r.contains(kAccel.name())) {
    const std::string& accel = p.get(kAccel);
    s.accel = accel == "shells" ? AccelKind::Shells
              : accel == "none" ? AccelKind::None
                                : AccelKind::Grid;
    s.grid_divisions = static_cast<int>(p.get(kGridDivisions));
  }
  if (r.contains(kPolygonKernel.name()))
    s.polygon_kernel = p.get(kPolygonKernel) == "ullner-quad" ? PolygonKernel::UllnerQuad
                                                              : PolygonKernel::Triangle;
  if (r.contains(kShellBranching.name())) {
    s.shell_branching = static_cast<int>(p.get(kShellBranching));
    s.shell_leaf_size = static_cast<int>(p.get(kShellLeafSize));
  }
  if (r.contains(kBezierIterations.name())) {
    s.bezier_iterations = static_cast<int>(p.get(kBezierIterations));
    s.bezier_culler_key_bits = static_cast<int>(p.get(kBezierCullerKeyBits));
    using Kind = kernels::WangArithmetic::Kind;
    const std::string arithmetic = p.get(kBezierArithmetic);
    s.bezier_arithmetic.kind = arithmetic == "float64" ? Kind::kFloat64
                               : arithmetic == "fixed" ? Kind::kFixed
                                                       : Kind::kFloat32;
    s.bezier_arithmetic.fixed.bits = static_cast<int>(p.get(kBezierFixedBits));
    s.bezier_arithmetic.fixed.integer_bits = static_cast<int>(p.get(kBezierFixedIntegerBits));
    if (s.bezier_arithmetic.fixed.integer_bits >= s.bezier_arithmetic.fixed.bits)
      throw InputError(std::string(kBezierFixedIntegerBits.name()), 0,
                       "must be less than bezier.fixed_bits (" +
                           std::to_string(s.bezier_arithmetic.fixed.bits) +
                           "): a fixed-point word needs a bit below the point");
  }
  s.scene_seed = read_scene_seed(r);
  s.shade.ambient = p.get(kAmbient);
  if (r.contains(kMaxDepth.name())) {
    s.shade.max_depth = static_cast<int>(p.get(kMaxDepth));
    s.shade.contribution_threshold = p.get(kContributionThreshold);
  }
  s.shade.light_intensity = p.get(kLightIntensity);
  s.view_azimuth_deg = p.get(kViewAzimuth);
  s.view_elevation_deg = p.get(kViewElevation);
  return s;
}

}  // namespace rtsim::functional
