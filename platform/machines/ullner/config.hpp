#pragma once
// The peripheral's parameters as the modules use them (read once from the registry).
#include <cstdint>
#include <systemc>

#include "firmware/bounds.hpp"
#include "modules/processor_timing.hpp"

namespace rtsim::platform::ullner {

struct PeripheralConfig {
  sc_core::sc_time intersect_interval;  ///< issue interval = stage time of the pipeline
  unsigned adder_stages = 1;            ///< 1 or 3 (Fig. 2-17)
  unsigned pipeline_stages = 17;        ///< physical depth, from adder_stages
  unsigned fetch_stages = 1;
  unsigned select_stages = 1;
  std::size_t ray_queue_depth = 16;
  std::size_t result_queue_depth = 16;
  bool shadow_early_exit = false;
  int grid_divisions = 0;      ///< 0: brute force
  sc_core::sc_time step_time;  ///< t_d
  unsigned indirection_stages = 1;
  bool lighting = true;
  unsigned rsqrt_stages = 2;
  sc_core::sc_time load_word_time;
  std::uint64_t memory_polygons = 0;  ///< capacity of the parameter memories
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

struct HostConfig {
  modules::ProcessorTiming timing;
};

}  // namespace rtsim::platform::ullner
