#pragma once
// ullner-pipeline: Ullner's ray-tracing pipeline (seed 000 §2.4, L684-L753). One polygon
// processor per polygon in a linear chain on bit-serial links; rays stream past the fixed
// polygons and each processor overwrites the description's intersection fields when its polygon
// is hit closer. The host at both ends (Fig. 2-23) is the peripheral's host, keeping many rays
// in flight; it loads the polygons by shifting them down the chain, dummies in the spares.
#include "platform/machine.hpp"

namespace rtsim::platform {

class UllnerPipeline final : public Machine {
 public:
  std::string name() const override { return "ullner-pipeline"; }
  std::string description() const override {
    return "Ullner's ray tracing pipeline: one intersection processor per polygon on "
           "bit-serial links, rays streaming past, host at both ends (seed 000 §2.4)";
  }
  std::string sample_scene() const override { return "builtin:ullner-cubes"; }
  void declare_params(params::ParamRegistry& registry) const override;
  FunctionalTwin make_twin(scenes::Scene& scene,
                           const params::ParamRegistry& registry) const override;
  RunResult run(scenes::Scene& scene, FunctionalTwin& twin, const params::ParamRegistry& registry,
                const RunOptions& opts) const override;
};

}  // namespace rtsim::platform
