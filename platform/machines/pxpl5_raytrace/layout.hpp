#pragma once
// Who is where on Pixel-Planes 5's ring and who owns which part of the image (seed 004 Fig. 1,
// L292-L310): the host (Sun-4), the master GP, the ray-caster GPs, the compositor GPs, the SIMD
// renderers and the frame buffer, in that order round the ring. The casters sample the screen on
// a lattice (firmware/tasks/sample_lattice.hpp: a ray every `finest` pixels at most). A
// compositor owns horizontal bands of `band_rows` image rows (640 x 64 in VOL2, L310; band b goes
// to compositor b mod C) and the lattice rows in them; a renderer owns a 128 x 128 tile of the
// display (L282: 20 of them tile 640 x 512) and reads the lattice positions around its pixels.
#include <vector>

#include "firmware/tasks/refinement_schedule.hpp"
#include "firmware/tasks/region_sampling.hpp"
#include "firmware/tasks/sample_lattice.hpp"
#include "params/registry.hpp"
#include "platform/machines/pxpl5_raytrace/messages.hpp"

namespace rtsim::platform::pxpl5 {

enum class Scheme { kRows, kSquares };
/// "rows" or "squares": assign.scheme's value.
const char* scheme_name(Scheme s);

struct Layout {
  int width = 0, height = 0;
  int casters = 1, compositors = 1;
  int band_rows = 64;
  int tile = 128;
  Scheme scheme = Scheme::kSquares;
  int square = 64;
  tasks::SamplingRule rule;
  int update_period = 1;  ///< partial updating: 1 (100%), 2 (50%) or 4 (25%)
  int refine_levels = 1;  ///< successive refinement's levels (refinement_schedule.hpp)

  /// The lattice, its extent a multiple of the coarsest level's spacing.
  tasks::SampleLattice lattice() const {
    return {width, height, rule.finest, 1 << (refine_levels - 1)};
  }

  int tiles_x() const { return (width + tile - 1) / tile; }
  int tiles_y() const { return (height + tile - 1) / tile; }
  int renderers() const { return tiles_x() * tiles_y(); }

  int host() const { return 0; }
  int master() const { return 1; }
  int caster(int k) const { return 2 + k; }
  int compositor(int k) const { return 2 + casters + k; }
  int renderer(int k) const { return 2 + casters + compositors + k; }
  int frame_buffer() const { return 2 + casters + compositors + renderers(); }
  int nodes() const { return frame_buffer() + 1; }

  /// The compositor (0..C-1) that owns image row y.
  int compositor_of_row(int y) const { return (y / band_rows) % compositors; }
  /// The compositor that owns lattice row j (the image row it lies on; the row past the image's
  /// last goes with the last).
  int compositor_of_lattice_row(int j) const;
  /// The renderer (0..R-1) whose tile holds pixel (x, y).
  int renderer_of(int x, int y) const { return (y / tile) * tiles_x() + x / tile; }
  /// Pixels renderer k owns.
  long pixels_of_renderer(int k) const;
  /// The lattice positions renderer k reads on the grid of every `step`-th position: within
  /// [i0, i1) x [j0, j1).
  tasks::LatticeRange lattice_of_renderer(int k, int step = 1) const;
  /// The renderers that read lattice column i (or row j: `rows`) on the grid of every `step`-th
  /// position, as tile columns (rows).
  std::vector<std::vector<int>> tiles_reading(bool rows, int step = 1) const;

  /// The frame's regions in screen order: sample rows (one lattice row each, L352) or squares
  /// of `square` pixels (L360), left to right, top to bottom, with their lattice positions.
  std::vector<Region> regions() const;
  /// Positions region `g` sends compositor k in frame `frame` of `schedule` (partial updating,
  /// refinement and all).
  long positions_sent(const Region& g, int k, const tasks::RefinementSchedule& schedule,
                      int frame) const;

  /// Declares what a layout is read from: caster_count, compositor_count, compositor.band_rows,
  /// assign.scheme, assign.square, sampling.*, update.fraction and refine.levels.
  static void declare_params(params::ParamRegistry& r);
  /// The layout a run's parameters give (its size is the run's: set after), with the sampling
  /// rule checked: a rule that cannot be followed is bad input (exit 2).
  static Layout read(const params::ParamRegistry& r);
  /// Only what the picture depends on (the functional twin reads it): the work handed out, the
  /// sampling rule, partial updating and refinement, checked as read() checks them; the GP
  /// counts and bands keep their defaults.
  static Layout read_sampling(const params::ParamRegistry& r);
};

}  // namespace rtsim::platform::pxpl5
