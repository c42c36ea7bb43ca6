#pragma once
// wang-bezier: Wang, Lewis & Hung's pipelined ray/Bezier-patch intersection machine (seed 002):
// a host that culls (ray, patch) pairs by the patch's box and issues them to an 11-stage
// pipeline of TMS320C6701 DSPs and a Culler ASIC, reading back the centre of the nearest
// surviving subpatch.
#include "platform/machine.hpp"

namespace rtsim::platform {

class WangBezier final : public Machine {
 public:
  std::string name() const override { return "wang-bezier"; }
  std::string description() const override {
    return "Wang, Lewis & Hung's ray/Bezier-patch pipeline: a host culling and issuing jobs to "
           "stage 0 and 10 loop stages of DSPs with a Culler ASIC (seed 002)";
  }
  std::string sample_scene() const override;
  void declare_params(params::ParamRegistry& registry) const override;
  FunctionalTwin make_twin(scenes::Scene& scene,
                           const params::ParamRegistry& registry) const override;
  RunResult run(scenes::Scene& scene, FunctionalTwin& twin, const params::ParamRegistry& registry,
                const RunOptions& opts) const override;
};

}  // namespace rtsim::platform
