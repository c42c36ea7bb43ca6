#pragma once
// The test of one candidate shape inside a search (brute force, Ullner's grid, Gaudet's shells).
// The functional renderer tests the kernels of its own geometry. A machine whose search runs on
// the functional structures but whose kernels read their operands out of the machine's memories
// supplies its own test, so that its answers come from the words its transactions carried
// (Ullner's peripheral: platform/machines/ullner_peripheral/parameter_memory_test.hpp).
#include <cstdint>

#include "firmware/hit.hpp"
#include "firmware/ray.hpp"
#include "firmware/trace_counters.hpp"

namespace rtsim::functional {

class CandidateTest {
 public:
  virtual ~CandidateTest() = default;
  /// Tests shape `slot` (an index into the geometry's shapes) over (t_min, t_max); on a hit
  /// fills `out` and returns true. Counts the test and its cost in `counters`.
  virtual bool test(std::uint32_t slot, const Ray& ray, double t_min, double t_max, SurfaceHit& out,
                    TraceCounters& counters) const = 0;
};

}  // namespace rtsim::functional
