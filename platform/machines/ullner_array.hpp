#pragma once
// ullner-array: Ullner's ray-tracing array (seed 000 §2.5, L755-L895). An R x C grid of
// processors on four bidirectional links; each owns a column of subvolumes along the depth axis
// (or a skewed assignment, with wrap links) and a block of the frame buffer; rays travel as
// messages between them, and the image is the sum of the contributions the result messages carry.
#include "platform/machine.hpp"

namespace rtsim::platform {

class UllnerArray final : public Machine {
 public:
  std::string name() const override { return "ullner-array"; }
  std::string description() const override {
    return "Ullner's ray tracing array: a grid of processors, each a CPU with an intersection "
           "unit owning a column of subvolumes, passing ray messages to its neighbours "
           "(seed 000 §2.5)";
  }
  std::string sample_scene() const override { return "builtin:ullner-cubes"; }
  /// No warm-up: its processors start their own rays at once, so there is no fill to wait out,
  /// and window completions bunch at the frame's end; a warm-up's windows only push the exact
  /// start later (measured: an error of 6% became 108% on ullner-sheets-1000 at K = 8,
  /// docs/sampling.md).
  int sample_warmup_rays(const params::ParamRegistry&) const override { return 0; }
  void declare_params(params::ParamRegistry& registry) const override;
  FunctionalTwin make_twin(scenes::Scene& scene,
                           const params::ParamRegistry& registry) const override;
  RunResult run(scenes::Scene& scene, FunctionalTwin& twin, const params::ParamRegistry& registry,
                const RunOptions& opts) const override;
};

}  // namespace rtsim::platform
