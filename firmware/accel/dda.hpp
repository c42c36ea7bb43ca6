#pragma once
// Ullner's 3-D DDA for moving between subvolumes (seed 000 Appendix B, L2112-L2171).
//
// Per axis, with r(t) = (r1 - r0) t + r0 and our unit direction d = r1 - r0 (so t is a
// distance), the grid planes x = ((x_max - x_min)/n_x) i_x + x_min (L2122) are crossed at
//   t = a_x i_x + b_x,  a_x = (x_max - x_min) / ((r1x - r0x) n_x),  b_x = (x_min - r0x)/(r1x - r0x)
// (L2128); likewise for y and z (L2132-L2134). Fig. B-1 (L2142-L2155) finds the first
// subvolume, Fig. B-2 (L2159-L2165) steps to the next one along the axis whose next crossing
// is smallest.
//
// Two variants:
//  * AsPrinted reproduces Figs. B-1/B-2 literally, with their errors (seed note 000 §4.6):
//    t_x := a_x i_x + b_x + |a_x| is the next crossing only for a_x < 0; entry exactly on a
//    boundary plane gives i = ceil(0) = 0 and is reported as a miss; strict < in all three
//    branches of Fig. B-2, so a tie fires no branch. Where the printed program would divide by
//    zero (an axis-parallel ray) or spin forever (a tie), this version stops and says so in
//    DdaResult, and a step bound makes it impossible to hang.
//  * Corrected fixes the five issues the note lists: (1) the next crossing is
//    a (i + [a > 0]) + b in 0-based cells, right for both signs of a; (2) the entry cell is
//    floor(f) for a > 0 and ceil(f) - 1 for a < 0, f = (t - b)/a, so an entry on a plane lands
//    in the cell the ray is moving into; (3) ties step every tied axis at once (the <= of the
//    note, generalised: a ray through a grid edge or corner moves diagonally and never visits
//    a cell it only touches at a point); (4) an axis-parallel ray has a = +-inf and never steps
//    that axis (a ray lying exactly in a grid plane is put in the cell above the plane, or the
//    last cell on the max face); (5) the entry t must be below the exit t, and the walk stops
//    at the exit t = min(t_max, box exit).
//
// Corrected visits exactly the subvolumes in which the ray segment (t_min, t_max) runs a
// positive length, in order of t, and steps = visited cells - 1.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <span>
#include <type_traits>

#include "firmware/accel/uniform_grid.hpp"
#include "firmware/cost.hpp"
#include "firmware/ray.hpp"

namespace rtsim::accel {

enum class DdaVariant : std::uint8_t {
  Corrected,  ///< the fixed algorithm (default)
  AsPrinted,  ///< Figs. B-1/B-2 exactly as printed, for fidelity experiments
};

/// What one traversal did. The auxiliary processor is charged t_d per step (seed 000 L654).
struct DdaResult {
  bool entered = false;             ///< at least one subvolume was visited
  bool stopped_by_visitor = false;  ///< the visitor returned true
  std::uint64_t cells_visited = 0;
  std::uint64_t steps = 0;  ///< executions of Fig. B-2 that moved to a new subvolume
  // Failure modes of the printed program (only AsPrinted sets these):
  bool division_by_zero = false;    ///< a direction component is 0: Fig. B-1 divides by 0
  bool stalled = false;             ///< a tie fired no branch of Fig. B-2: the loop would spin
  bool step_bound_reached = false;  ///< more steps than any ray can take (never expected)
};

/// Machine-neutral cost of the DDA (for the auxiliary processor model).
/// Fig. B-1 per axis: a = (width/n)/d (1 div; width/n is per grid), b = (min - r0)/d (1 add,
/// 1 div), a n + b (1 mul, 1 add), min and max (2 compares), (t - b)/a (1 add, 1 div), the
/// ceiling (1 instruction), a i + b + |a| (1 mul, 2 adds); then 6 range compares (instructions).
inline constexpr Cost kDdaSetupCost{.fp_add = 3 * 7,
                                    .fp_mul = 3 * 2,
                                    .fp_div = 3 * 3,
                                    .fp_sqrt = 0,
                                    .mem_words = 9,  ///< box min/max, n per axis
                                    .instructions = 3 + 6};
/// Fig. B-2: two compares to find the smallest of tx, ty, tz, one add (t += |a|), one index
/// increment and one range test (instructions).
inline constexpr Cost kDdaStepCost{
    .fp_add = 3, .fp_mul = 0, .fp_div = 0, .fp_sqrt = 0, .mem_words = 0, .instructions = 2};

/// Where a walk stopped, to go on from there: the subvolume it was in, the t at which the ray
/// entered it (the visitor's t_enter there), and the subvolumes the walk had visited by then,
/// that one included (DdaResult::cells_visited at that visit). A processor that hands a ray on
/// to the one owning its next subvolume (ullner-array) gives it this, so that the next does not
/// walk again from the ray's origin.
struct DdaPlace {
  CellIndex cell{};
  double t_enter = 0.0;
  std::uint64_t visited = 0;  ///< 0: no place (walk from the start)
};

/// Walks the subvolumes of a UniformGrid along a ray.
///
/// visit(CellIndex cell, std::span<const std::uint32_t> polygon_addresses, double t_enter,
///       double t_exit) is called for each subvolume in order; returning true stops the walk
///       (a visitor returning void never stops it).
class Dda {
 public:
  explicit Dda(const UniformGrid& grid, DdaVariant variant = DdaVariant::Corrected)
      : grid_(&grid), variant_(variant) {}

  const UniformGrid& grid() const { return *grid_; }
  DdaVariant variant() const { return variant_; }
  /// No ray crosses more than n_x + n_y + n_z planes; the walk gives up beyond this.
  std::uint64_t step_bound() const {
    const GridDivisions n = grid_->divisions();
    return static_cast<std::uint64_t>(n.x) + static_cast<std::uint64_t>(n.y) +
           static_cast<std::uint64_t>(n.z) + 3;
  }

  template <class Visit>
  DdaResult traverse(const Ray& ray, double t_min, double t_max, Visit&& visit) const {
    return variant_ == DdaVariant::Corrected ? traverse_corrected(ray, t_min, t_max, visit)
                                             : traverse_as_printed(ray, t_min, t_max, visit);
  }
  /// traverse(), going on from `at` (a place a walk of this ray with these limits reached): the
  /// visitor is called from `at.cell` on, and the result (cells visited, steps) is the whole
  /// walk's, as if it had visited the cells before without stopping. The corrected walk starts
  /// there (its state is the cell: each crossing is worked out from the cell's index, L2128);
  /// the printed one walks from the start and skips the cells before.
  template <class Visit>
  DdaResult traverse_from(const Ray& ray, double t_min, double t_max, const DdaPlace& at,
                          Visit&& visit) const {
    if (at.visited == 0) return traverse(ray, t_min, t_max, visit);
    if (variant_ == DdaVariant::Corrected) return traverse_corrected(ray, t_min, t_max, visit, &at);
    std::uint64_t calls = 0;
    auto from_at = [&](const CellIndex& c, std::span<const std::uint32_t> s, double t0, double t1) {
      return ++calls >= at.visited && call(visit, c, s, t0, t1);
    };
    return traverse_as_printed(ray, t_min, t_max, from_at);
  }

 private:
  template <class Visit>
  static bool call(Visit& visit, const CellIndex& c, std::span<const std::uint32_t> s, double t0,
                   double t1) {
    if constexpr (std::is_void_v<decltype(visit(c, s, t0, t1))>) {
      visit(c, s, t0, t1);
      return false;
    } else {
      return static_cast<bool>(visit(c, s, t0, t1));
    }
  }

  template <class Visit>
  DdaResult traverse_corrected(const Ray& ray, double t_min, double t_max, Visit& visit,
                               const DdaPlace* from = nullptr) const;
  template <class Visit>
  DdaResult traverse_as_printed(const Ray& ray, double t_min, double t_max, Visit& visit) const;

  const UniformGrid* grid_;
  DdaVariant variant_;
};

template <class Visit>
DdaResult Dda::traverse_corrected(const Ray& ray, double t_min, double t_max, Visit& visit,
                                  const DdaPlace* from) const {
  DdaResult res;
  if (!is_finite(ray.origin) || !is_finite(ray.direction)) return res;
  const Bounds& box = grid_->box();
  const GridDivisions n = grid_->divisions();

  double a[3], b[3], t_next[3];
  int i[3], step[3];
  bool moves[3];
  double t_enter = t_min;
  double t_exit = t_max;
  for (int k = 0; k < 3; ++k) {
    const double d = ray.direction[k];
    const double o = ray.origin[k];
    // a_k = (max - min) / ((r1 - r0) n),  b_k = (min - r0) / (r1 - r0)   (L2128-L2134)
    a[k] = (box.hi[k] - box.lo[k]) / (d * n[k]);
    b[k] = (box.lo[k] - o) / d;
    moves[k] = d != 0.0 && std::isfinite(a[k]) && std::isfinite(b[k]);
    if (!moves[k]) {
      // Fix 4: axis-parallel (or so nearly parallel that a overflows): a = +-inf, never step.
      if (!(o >= box.lo[k] && o <= box.hi[k])) return res;  // outside this slab for all t
      const double f = (o - box.lo[k]) / (box.hi[k] - box.lo[k]) * n[k];
      // A ray lying in a grid plane belongs to the cell above it (the last cell on max).
      i[k] = static_cast<int>(std::clamp(std::floor(f), 0.0, static_cast<double>(n[k] - 1)));
      step[k] = 0;
      t_next[k] = kInfinity;
      continue;
    }
    // The ray is inside the slab between the crossings of planes 0 and n (L2136, Fig. B-1:
    // t := max(t, min(b, a n + b))); its exit is the other one.
    const double t_plane0 = b[k];
    const double t_planen = a[k] * n[k] + b[k];
    t_enter = std::max(t_enter, std::min(t_plane0, t_planen));
    t_exit = std::min(t_exit, std::max(t_plane0, t_planen));
  }
  // Fix 5: the ray must run a positive length inside the box (this also rejects NaN limits).
  if (!(t_enter < t_exit)) return res;

  for (int k = 0; k < 3; ++k) {
    if (!moves[k]) continue;
    step[k] = a[k] > 0.0 ? 1 : -1;
    if (from) {
      // Going on from a place this walk reached: its cell is the whole state (every crossing
      // is worked out from the indices, below and at each step).
      i[k] = from->cell[k];
    } else {
      // Solve t = a i + b for i (L2136). Fix 2: the cell the ray moves into from t_enter.
      const double f = (t_enter - b[k]) / a[k];
      const double cell = a[k] > 0.0 ? std::floor(f) : std::ceil(f) - 1.0;
      i[k] = static_cast<int>(std::clamp(cell, 0.0, static_cast<double>(n[k] - 1)));
    }
    // Fix 1: the next plane is i+1 when moving up, i when moving down (0-based cells).
    t_next[k] = a[k] * (i[k] + (step[k] > 0 ? 1 : 0)) + b[k];
    // Rounding in f can leave us one cell short (its far plane at or before t_enter): settle.
    // (A place the walk reached was settled then.)
    while (!from && t_next[k] <= t_enter) {
      i[k] += step[k];
      if (i[k] < 0 || i[k] >= n[k]) return res;
      t_next[k] = a[k] * (i[k] + (step[k] > 0 ? 1 : 0)) + b[k];
    }
  }
  double t_cell = from ? from->t_enter : t_enter;
  if (from) {
    res.cells_visited = from->visited - 1;
    res.steps = from->visited - 1;  // corrected: steps = visited cells - 1
  }

  const std::uint64_t bound = step_bound();
  for (;;) {
    const double t_step = std::min(t_next[0], std::min(t_next[1], t_next[2]));
    const CellIndex c{i[0], i[1], i[2]};
    res.entered = true;
    ++res.cells_visited;
    if (call(visit, c, grid_->cell(c), t_cell, std::min(t_step, t_exit))) {
      res.stopped_by_visitor = true;
      return res;
    }
    if (t_step >= t_exit) return res;  // Fix 5: leaves the box or reaches t_max
    if (res.steps >= bound) {
      res.step_bound_reached = true;
      return res;
    }
    // Fig. B-2 with fix 3: every axis whose crossing is the smallest steps now.
    for (int k = 0; k < 3; ++k) {
      if (t_next[k] != t_step) continue;
      i[k] += step[k];
      if (i[k] < 0 || i[k] >= n[k]) return res;  // cannot happen before t_exit; guard only
      // t = a i + b at the next plane (L2128). Fig. B-2 adds |a| instead; recomputing keeps
      // the crossing identical to the one the exit test uses, with no drift over many steps.
      t_next[k] = a[k] * (i[k] + (step[k] > 0 ? 1 : 0)) + b[k];
    }
    ++res.steps;
    t_cell = t_step;
  }
}

template <class Visit>
DdaResult Dda::traverse_as_printed(const Ray& ray, double t_min, double /*t_max*/,
                                   Visit& visit) const {
  // Literal Figs. B-1/B-2 (seed 000 L2142-L2165), 1-based indices 1..n as printed. The printed
  // program has no t_max: it walks until an index leaves 1..n ("until the ray travels out of
  // the image space", L594).
  DdaResult res;
  if (!is_finite(ray.origin) || !is_finite(ray.direction)) return res;
  const Bounds& box = grid_->box();
  const GridDivisions n = grid_->divisions();
  for (int k = 0; k < 3; ++k) {
    if (ray.direction[k] == 0.0) {
      res.division_by_zero = true;  // (r1x - r0x) = 0 in a_x and b_x of Fig. B-1
      return res;
    }
  }
  // t := 0 (the ray origin; we start at t_min, 0 for a vision ray).
  double t = t_min;
  double a[3], b[3], tk[3];
  double idx[3];  // i_x as a real until the range test (ceil of a far-away entry can overflow int)
  for (int k = 0; k < 3; ++k) {
    // ax := (xmax - xmin)/((r1x - r0x) nx);  bx := (xmin - r0x)/(r1x - r0x);
    a[k] = (box.hi[k] - box.lo[k]) / (ray.direction[k] * n[k]);
    b[k] = (box.lo[k] - ray.origin[k]) / ray.direction[k];
    // t := max(t, min(bx, ax*nx + bx));
    t = std::max(t, std::min(b[k], a[k] * n[k] + b[k]));
  }
  for (int k = 0; k < 3; ++k) {
    // ix := ceil((t - bx)/ax);  tx := ax*ix + bx + |ax|;
    idx[k] = std::ceil((t - b[k]) / a[k]);
    tk[k] = a[k] * idx[k] + b[k] + std::fabs(a[k]);
  }
  // if ix < 1 or nx < ix or ... then the ray misses the scene.
  for (int k = 0; k < 3; ++k) {
    if (!(idx[k] >= 1.0 && idx[k] <= static_cast<double>(n[k]))) return res;
  }
  int i[3] = {static_cast<int>(idx[0]), static_cast<int>(idx[1]), static_cast<int>(idx[2])};
  auto sgn = [](double v) { return v > 0.0 ? 1 : (v < 0.0 ? -1 : 0); };

  double t_cell = t;
  const std::uint64_t bound = step_bound();
  for (;;) {
    const CellIndex c{i[0] - 1, i[1] - 1, i[2] - 1};
    res.entered = true;
    ++res.cells_visited;
    const double t_out = std::min(tk[0], std::min(tk[1], tk[2]));
    if (call(visit, c, grid_->cell(c), t_cell, t_out)) {
      res.stopped_by_visitor = true;
      return res;
    }
    if (res.steps >= bound) {
      res.step_bound_reached = true;
      return res;
    }
    // Fig. B-2, strict < in every branch (ef = else-if).
    int k = -1;
    if (tk[0] < std::min(tk[1], tk[2])) {
      k = 0;
    } else if (tk[1] < std::min(tk[0], tk[2])) {
      k = 1;
    } else if (tk[2] < std::min(tk[0], tk[1])) {
      k = 2;
    }
    if (k < 0) {
      res.stalled = true;  // no branch fires: the printed loop repeats forever
      return res;
    }
    t_cell = tk[k];
    i[k] += sgn(a[k]);
    tk[k] += std::fabs(a[k]);
    if (i[k] < 1 || i[k] > n[k]) return res;  // out of the modelling space
    ++res.steps;
  }
}

}  // namespace rtsim::accel
