#pragma once
// The figures of Ullner's ray-tracing peripheral (seed 000 §2.3.4, L586-L680; note 000 §2.5,
// §7.4): intersection interval and latency, brute-force time per ray and frame, and the grid
// subdivision curve of Fig. 2-18 against the analytic model of L652.
#include <vector>

#include "firmware/accel/grid_divisions.hpp"
#include "platform/validation/curve_shape.hpp"
#include "platform/validation/validation.hpp"

namespace rtsim::validation {

/// Machine name of Ullner's peripheral in `rtsim run`.
inline constexpr const char* kUllnerMachine = "ullner-peripheral";
/// 1000 polygons of total area 2 as random squares: the brute-force figures (every polygon
/// streams through the pipe, so only the count matters).
inline constexpr const char* kUllnerRandomScene = "builtin:ullner-random-1000";
/// Fig. 2-18's hypothetical scene read literally (seed 000 L654): a_t = 2 as two sheets that
/// "stretch through the modeling space twice", rays travelling d_r = 1/2 before a hit; 968
/// polygons (two 22 x 22 sheets). Random small squares (kUllnerRandomScene) break the model's
/// occupied-subvolume assumption (L642): there the minimum is ~22 us (docs/validation.md).
inline constexpr const char* kUllnerSheetsScene = "builtin:ullner-sheets-1000";
inline constexpr double kUllnerPolygons = 1000.0;  ///< n_p of L590 and L654
/// Fig. 2-19's scene: 83 randomly oriented cubes (seed 000 L668).
inline constexpr const char* kUllnerCubesScene = "builtin:ullner-cubes";
/// 512 x 512, one ray per pixel (seed 000 L590): the frame of V5.
inline constexpr int kUllnerFrameSide = 512;
/// Quick mode's image side: 4096 primary rays, so a mean per ray has a sampling error of a
/// few tenths of a percent while each run takes well under a second.
inline constexpr int kUllnerQuickSide = 64;

/// The n_s swept for Fig. 2-18: 1..30 in full mode; in quick mode a subset dense around the
/// thesis's minimum (11) and spread to both ends, so argmin and steepness are still defined.
std::vector<int> fig2_18_divisions(bool quick);
/// n_s swept on the cubes of Fig. 2-19 (fewer points: only an interior minimum is checked).
std::vector<int> fig2_19_divisions(bool quick);

/// Ullner's t_r(n_s) (seed 000 L652), in microseconds, at each n_s.
std::vector<CurvePoint> fig2_18_model_curve(const std::vector<int>& n_s,
                                            const accel::UllnerGridModel& model = {},
                                            double n_p = kUllnerPolygons);

}  // namespace rtsim::validation
