#pragma once
// The values of the peripheral's parameters as its modules use them: read once by
// Peripheral::read_settings from the parameters Peripheral::declare_params declares (the
// defaults are there, not here), plus the modelling space the scene gives.
#include <cstdint>
#include <string>
#include <systemc>

#include "firmware/bounds.hpp"

namespace rtsim::platform::ullner {

struct PeripheralSettings {
  sc_core::sc_time intersect_interval;  ///< issue interval = stage time of the pipeline
  unsigned adder_stages;                ///< 1 or 3 (Fig. 2-17)
  unsigned pipeline_stages;             ///< physical depth, from adder_stages
  unsigned fetch_stages;
  unsigned select_stages;
  std::size_t ray_queue_depth;
  bool shadow_early_exit;
  int grid_divisions;          ///< 0: brute force
  bool dda_as_printed;         ///< Appendix B's stepping exactly as printed (grid.dda)
  sc_core::sc_time step_time;  ///< t_d
  unsigned indirection_stages;
  bool lighting;
  unsigned rsqrt_stages;
  sc_core::sc_time load_word_time;
  std::size_t memory_polygons;       ///< the parameter memories' capacity
  std::string memory_polygons_name;  ///< its parameter, for a message
  /// The modelling space (the grid's box; the scene's bounds in brute force): d_r is measured
  /// from where a primary ray enters it, in units of its largest side.
  Bounds modelling_space;

  /// Physical stages of the intersection computation (seed 000 L588, Fig. 2-17): t needs a
  /// multiply, two additions and a long division (4 stages with 1-stage adders, 6 with 3);
  /// p_r a multiply and an addition; u (and v alongside) a multiply, two additions, a multiply
  /// (A^2), an addition (A^2 - B), a square root (2) and an addition. With adder depth a:
  /// (4 + 3a) + (1 + a) + (4 + 4a) = 9 + 8a: 17 for a = 1, 33 for a = 3.
  static unsigned stages_for_adder(unsigned a) { return 9 + 8 * a; }
};

}  // namespace rtsim::platform::ullner
