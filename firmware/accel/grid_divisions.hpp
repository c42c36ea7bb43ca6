#pragma once
// Choosing the number of subvolumes per axis for Ullner's grid.
//
// Ullner's model of the time to trace one ray (seed 000 L648-L652):
//   t_r = [(n_s - 1) d_r + 1] t_d
//       + ((1 - 1/n_s) d_r n_s^-2 + [(n_s - 1) sqrt(a_t) + 1]^-2) n_p t_i + t_l
// For large n_s the stepping term grows as n_s d_r t_d and the intersection term falls as
// (d_r + 1/a_t) n_p t_i / n_s^2, so the minimum is at
//   n_s^3 = 2 n_p t_i (d_r + 1/a_t) / (d_r t_d),   i.e.  n_s = k cbrt(n_p),
//   k = cbrt(2 t_i (d_r + 1/a_t) / (d_r t_d)).
// With the thesis's values (t_i = 1/3 us, t_d = 1 us, d_r = 1/2, a_t = 2; L654) k = 1.1006, and
// n_p = 1000 gives n_s = 11.0 — exactly the minimum Ullner reports for Fig. 2-18 ("eleven
// subdivisions per axis", L654). So the default density is Ullner's own optimum, not a
// tuning from modern grids. (He notes the curve is steeper left of the minimum, "less costly
// to overestimate", L656; the exact L652 minimum for n_p = 1000 is still n_s = 11, so the
// per-axis counts are rounded to nearest, which reproduces it.)
#include <cstddef>

#include "firmware/accel/uniform_grid.hpp"
#include "firmware/bounds.hpp"

namespace rtsim::accel {

/// Parameters of Ullner's per-ray time model (seed 000 L608-L654), defaults from L654.
struct UllnerGridModel {
  double t_i_us = 1.0 / 3.0;  ///< time per ray/polygon intersection (L654, L588)
  double t_d_us = 1.0;        ///< time to step to the next subvolume (L654, an assumption there)
  double t_l_us = 5.6;        ///< pipeline latency (L654, L588)
  double d_r = 0.5;           ///< mean ray travel as a fraction of the modelling space (L654)
  double a_t = 2.0;           ///< overall surface area, unit modelling space (L654)

  /// Estimated time per ray for n_s subdivisions per axis and n_p polygons (L652).
  double time_per_ray_us(int n_s, double n_p) const;
  /// k with n_s ~= k cbrt(n_p) at the large-n_s minimum of time_per_ray_us (derivation above).
  double density() const;
};

/// Ullner's optimum density with the thesis's parameters: cbrt(2 (1/3) (1/2 + 1/2) / (1/2)).
inline constexpr double kUllnerGridDensity = 1.1006424;

/// Divisions for `primitive_count` primitives in `box`: cells are as close to cubes as the box
/// allows, with side s chosen so a cube of the box's volume would get k cbrt(N) cells per axis
/// (s = cbrt(V / (k^3 N))), each axis n = max(1, round(extent / s)). Flat axes get 1 division
/// and the side is computed over the remaining axes. The total is capped at max_cells by
/// growing s. N = 0 gives 1x1x1.
GridDivisions choose_divisions(const Bounds& box, std::size_t primitive_count,
                               double density = kUllnerGridDensity,
                               std::size_t max_cells = std::size_t{1} << 24);

}  // namespace rtsim::accel
