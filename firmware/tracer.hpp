#pragma once
// What a shade task needs from the rest of the machine: the closest hit of a ray, and whether
// anything blocks a light ray. The functional renderer implements it with the kernels and an
// acceleration structure; each machine's functional twin implements it with that machine's own
// geometry conversion.
#include "firmware/hit.hpp"
#include "firmware/ray.hpp"
#include "firmware/trace_counters.hpp"

namespace rtsim {

class Tracer {
 public:
  virtual ~Tracer() = default;
  /// Closest hit with t in (t_min, t_max); false on a miss.
  virtual bool closest_hit(const Ray& ray, double t_min, double t_max, Hit& hit,
                           TraceCounters& counters) const = 0;
  /// Any hit with t in (t_min, t_max): the shadow-ray test ("any hit, not closest").
  virtual bool any_hit(const Ray& ray, double t_min, double t_max,
                       TraceCounters& counters) const = 0;
};

}  // namespace rtsim
