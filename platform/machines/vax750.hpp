#pragma once
// vax-750: the sequential baseline. One DEC VAX-11/750 with floating-point unit runs the whole
// ray tracer, with Gaudet's measured costs (seed 001 L310-L326): T_i = 429 us per ray/object
// intersection test and T_s = 710 us per ray spawned. It tests every object for every ray
// (brute force), so a frame takes T_t = R_t (T_s + T_i O) (seed 001 L326): the reference for
// "N times faster than the VAX".
#include "platform/machine.hpp"

namespace rtsim::platform {

class Vax750 final : public Machine {
 public:
  std::string name() const override { return "vax-750"; }
  std::string description() const override {
    return "DEC VAX-11/750 + FPU running the sequential ray tracer: Gaudet's baseline "
           "(429 us per intersection, 710 us per ray; seed 001 L317-L318)";
  }
  std::string sample_scene() const override { return "builtin:npp-412"; }
  void declare_params(params::ParamRegistry& registry) const override;
  FunctionalTwin make_twin(scenes::Scene& scene,
                           const params::ParamRegistry& registry) const override;
  RunResult run(scenes::Scene& scene, FunctionalTwin& twin, const params::ParamRegistry& registry,
                const RunOptions& opts) const override;
};

}  // namespace rtsim::platform
