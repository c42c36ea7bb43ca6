// The parameters a pxpl5-raytrace Layout is read from, each named once: how many of each GP,
// who owns which rows, the regions the master GP hands out and the sampling rule.
#include <string>

#include "common/input_error.hpp"
#include "modules/module_params.hpp"
#include "platform/machines/pxpl5_raytrace/layout.hpp"

namespace rtsim::platform::pxpl5 {

namespace {

const modules::CountParam kCasters(
    {.name = "caster_count",
     .default_value = "16",
     .min = "1",
     .max = "1024",
     .unit = "GPs",
     .description = "Ray-caster GPs (i860s with the scene replicated)",
     .source = "seed 004 L369: Fig. 9's system has 21 GPs, 4 of them compositors, one master"});
const modules::CountParam kCompositors(
    {.name = "compositor_count",
     .default_value = "4",
     .min = "1",
     .max = "256",
     .unit = "GPs",
     .description = "Compositor GPs, each owning every compositor_count-th band of rows",
     .source = "seed 004 L369 (4 in Fig. 9; 8 typical, L310)"});
const modules::IntParam kBandRows(
    {.name = "compositor.band_rows",
     .default_value = "64",
     .min = "1",
     .max = "16384",
     .unit = "rows",
     .description = "Rows of one band; band b belongs to compositor b mod compositor_count",
     .source = "seed 004 L310 (640 x 64 bands)"});
const modules::ChoiceParam kScheme(
    {.name = "assign.scheme",
     .default_value = "squares",
     .allowed = {"rows", "squares"},
     .description = "Work the master GP hands out: sample rows, in order from the top (L352), or "
                    "square regions (L360)",
     .source = "seed 004 L352, L360",
     .affects_image = true});
const modules::CountParam kSquare(
    {.name = "assign.square",
     .default_value = "64",
     .min = "1",
     .max = "4096",
     .unit = "pixels",
     .description =
         "Side of a square region in pixels (VOL2: 64, 1/80 of 640 x 512). With adaptive "
         "sampling a square also casts its right and bottom edges, shared with its neighbours: "
         "65 x 65 pixels, \"two edges of replicated rays\"",
     .source = "seed 004 L360",
     .affects_image = true});
const modules::CountParam kFinest(
    {.name = "sampling.finest",
     .default_value = "1",
     .min = "1",
     .max = "64",
     .unit = "pixels",
     .description = "Pixels between rays at the finest level, a power of two: 1 casts a ray per "
                    "pixel (the image of every other machine); VOL2 ends at one ray per 4 x 4; "
                    "the renderers resample to display pixels",
     .source = "seed 004 L369 (4; rows every 8 x 8 or 4 x 4)",
     .affects_image = true});
const modules::CountParam kStart(
    {.name = "sampling.start",
     .default_value = "0",
     .min = "0",
     .max = "256",
     .unit = "pixels",
     .description = "Pixels between rays before adaptive refinement, squares only (rows cannot "
                    "adapt, L352): larger than sampling.finest turns adaptive sampling on; 0 is "
                    "sampling.finest (no refinement)",
     .source = "seed 004 L369 (16: one ray per 16 x 16 refined to 4 x 4)",
     .affects_image = true});
const modules::RealParam kThreshold(
    {.name = "sampling.threshold",
     .default_value = "0.05",
     .min = "0",
     .max = "1000",
     .unit = "radiance",
     .description =
         "Colour difference between two corner samples (any channel) that refines a square",
     .source = "seed 004 L362 (a user-defined threshold; 0.05 is about 13 of 255 display "
               "levels: an assumption)",
     .affects_image = true});
const modules::ChoiceParam kSubdivision(
    {.name = "sampling.subdivision",
     .default_value = "partial",
     .allowed = {"partial", "conventional"},
     .description = "Refinement of a square whose corners differ: new samples only between "
                    "differing pairs and the centre (partial), or all five (conventional)",
     .source = "seed 004 L362, Fig. 8 (L358)",
     .affects_image = true});
const modules::FlagParam kObjectEdges(
    {.name = "sampling.object_edges",
     .default_value = "true",
     .description = "Corner samples that hit different primitives differ whatever their colour "
                    "(edges and intersection curves are refined)",
     .source = "seed 004 L364 (isosurface encoding; here the primitive hit)",
     .affects_image = true});
const modules::ChoiceParam kUpdateFraction(
    {.name = "update.fraction",
     .default_value = "100",
     .allowed = {"100", "50", "25"},
     .unit = "percent",
     .description = "Partial updating: the share of lattice positions cast each frame, on a "
                    "regular grid (a modulus of the position with the frame number); the "
                    "compositors keep the rest from earlier frames. The first frame casts all",
     .source = "seed 004 L373-L379",
     .affects_image = true});

const modules::CountParam kRefineLevels(
    {.name = "refine.levels",
     .default_value = "1",
     .min = "1",
     .max = "6",
     .unit = "levels",
     .description =
         "Successive refinement: resolution levels of the image, the coarsest a ray every "
         "2^(levels-1) lattice steps, each finer one halving it down to sampling.finest. While "
         "the view changes, frames cast and display the coarsest; while it rests, each frame "
         "casts the next level's new positions (a share of them with partial updating) and is "
         "displayed at the finest level complete. 1: every frame at sampling.finest. Uniform "
         "sampling only",
     .source = "seed 004 L288, L312 (the array of composited samples sent to the splat "
               "processors \"is thus of variable size\"); assumption: a level halves the "
               "spacing (Fig. 9's 8 x 8 and 4 x 4)",
     .affects_image = true});

[[noreturn]] void bad_param(const modules::ModuleParams& p, const params::ParamSpec& spec,
                            const std::string& what) {
  throw InputError(spec.name + " (set at " + p.where_set(spec.name) + ")", 0,
                   "pxpl5-raytrace: " + what);
}

bool power_of_two(long v) { return v > 0 && (v & (v - 1)) == 0; }

/// Checks the sampling rule `lay` gives against its regions (L352-L379).
void check_rule(const modules::ModuleParams& p, Layout& lay) {
  const auto square = static_cast<long>(lay.square);
  const std::string finest = kFinest.name(), start = kStart.name(), sq = kSquare.name();
  if (!power_of_two(lay.rule.finest))
    bad_param(p, kFinest.spec(),
              "the pixels between rays must be a power of two (1, 2, 4, 8, ...)");
  if (lay.scheme == Scheme::kRows) {
    lay.rule.start = lay.rule.finest;  // rows preclude adaptive sampling (L352)
  } else {
    if (square % lay.rule.finest != 0)
      bad_param(p, kFinest.spec(),
                "a square of " + sq + " = " + std::to_string(square) +
                    " pixels must hold a whole number of lattice steps of " + finest + " = " +
                    std::to_string(lay.rule.finest));
    if (lay.rule.adaptive()) {
      if (!power_of_two(lay.rule.start))
        bad_param(p, kStart.spec(), "the pixels between rays must be a power of two");
      if (square % lay.rule.start != 0)
        bad_param(p, kStart.spec(),
                  "adaptive squares of " + sq + " = " + std::to_string(square) +
                      " pixels are cut into cells of " + start + " = " +
                      std::to_string(lay.rule.start) + ": it must divide the square");
      if (lay.update_period > 1)
        bad_param(p, kUpdateFraction.spec(),
                  "partial updating casts a fixed share of the lattice each frame, and adaptive "
                  "subdivision needs every corner of a cell in the same frame: use one of them "
                  "(" +
                      start + " = " + finest + " for partial updating)");
    }
  }
  if (lay.refine_levels > 1 && lay.rule.adaptive())
    bad_param(p, kRefineLevels.spec(),
              "successive refinement casts a level's grid over frames, and adaptive subdivision "
              "refines each cell within one frame: use one of them (" +
                  start + " = " + finest + " for successive refinement)");
  if (lay.rule.start < lay.rule.finest)
    bad_param(p, kStart.spec(),
              "rays start at most as close as they end: " + start + " (" +
                  std::to_string(lay.rule.start) + ") must be at least " + finest + " (" +
                  std::to_string(lay.rule.finest) + ")");
}

}  // namespace

const char* scheme_name(Scheme s) { return s == Scheme::kRows ? "rows" : "squares"; }

void Layout::declare_params(params::ParamRegistry& r) {
  const modules::ParamDecls top(r, "", false);
  top.add(kCasters);
  top.add(kCompositors);
  top.add(kBandRows);
  top.add(kScheme);
  top.add(kSquare);
  top.add(kFinest);
  top.add(kStart);
  top.add(kThreshold);
  top.add(kSubdivision);
  top.add(kObjectEdges);
  top.add(kUpdateFraction);
  top.add(kRefineLevels);
}

Layout Layout::read(const params::ParamRegistry& r) {
  const modules::ModuleParams p(r, "");
  Layout lay = read_sampling(r);
  lay.casters = static_cast<int>(p.get(kCasters));
  lay.compositors = static_cast<int>(p.get(kCompositors));
  lay.band_rows = static_cast<int>(p.get(kBandRows));
  return lay;
}

Layout Layout::read_sampling(const params::ParamRegistry& r) {
  const modules::ModuleParams p(r, "");
  Layout lay;
  lay.scheme = p.get(kScheme) == scheme_name(Scheme::kRows) ? Scheme::kRows : Scheme::kSquares;
  lay.square = static_cast<int>(p.get(kSquare));
  lay.rule.finest = static_cast<int>(p.get(kFinest));
  lay.rule.start = static_cast<int>(p.get(kStart));
  if (lay.rule.start == 0) lay.rule.start = lay.rule.finest;
  lay.rule.threshold = p.get(kThreshold);
  lay.rule.object_edges = p.get(kObjectEdges);
  lay.rule.subdivision = p.get(kSubdivision) == "conventional" ? tasks::Subdivision::kConventional
                                                               : tasks::Subdivision::kPartial;
  lay.update_period = 100 / static_cast<int>(std::stol(p.get(kUpdateFraction)));
  lay.refine_levels = static_cast<int>(p.get(kRefineLevels));
  check_rule(p, lay);
  return lay;
}

}  // namespace rtsim::platform::pxpl5
