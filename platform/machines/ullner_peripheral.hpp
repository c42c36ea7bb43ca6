#pragma once
// ullner-peripheral: Ullner's ray tracing peripheral (seed 000 §2.3, L458-L680) attached to a
// medium-sized host. The host runs two tasks (vision-ray generation; result processing and
// shading) with a ray queue and a result queue between it and the peripheral; the peripheral
// fetches polygons from 20 parallel parameter memories into the intersection pipeline (13
// logical stages; 17 or 33 physical, one intersection per 1/3 us), keeps the closest valid hit
// (any hit for shadow rays), and has the lighting extension. With peripheral.grid.divisions > 0
// the grid auxiliary processor feeds it the polygon addresses of the subvolumes along the ray.
#include "platform/machine.hpp"

namespace rtsim::platform {

class UllnerPeripheral final : public Machine {
 public:
  std::string name() const override { return "ullner-peripheral"; }
  std::string description() const override {
    return "Ullner's ray tracing peripheral with host, queues, 20 parameter memories, the "
           "intersection pipeline, lighting extension and optional grid auxiliary processor "
           "(seed 000 §2.3)";
  }
  std::string sample_scene() const override { return "builtin:ullner-cubes"; }
  void declare_params(params::ParamRegistry& registry) const override;
  FunctionalTwin make_twin(scenes::Scene& scene,
                           const params::ParamRegistry& registry) const override;
  RunResult run(scenes::Scene& scene, FunctionalTwin& twin, const params::ParamRegistry& registry,
                const RunOptions& opts) const override;
};

}  // namespace rtsim::platform
