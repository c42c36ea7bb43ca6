#pragma once
// gaudet-pert: Gaudet's multi-PERT machine (seed 001, Chapters 4-6). N PERTs — each a ring of
// ShadeProcessor -> ShellProcessor -> PrimProcessor (L841) — get the three disjoint data sets
// (shade, shell, prim) from three Broadcast Processors cycling over three broadcast buses,
// adaptively or not, or (the baseline) hold them in their own memories. A control processor
// preprocesses the scene, loads the broadcasters and starts the frame. See docs/machines.md.
#include "platform/machine.hpp"

namespace rtsim::platform {

class GaudetPert final : public Machine {
 public:
  std::string name() const override { return "gaudet-pert"; }
  std::string description() const override {
    return "Gaudet's multi-PERT machine: N rings of Shade/Shell/Prim processors fed by three "
           "broadcast buses (seed 001, SFU 1985)";
  }
  std::string sample_scene() const override { return "builtin:npp-412"; }
  void declare_params(params::ParamRegistry& registry) const override;
  FunctionalTwin make_twin(scenes::Scene& scene,
                           const params::ParamRegistry& registry) const override;
  RunResult run(scenes::Scene& scene, FunctionalTwin& twin, const params::ParamRegistry& registry,
                const RunOptions& opts) const override;
  /// A sampled window spans every PERT: each takes every N-th scanline (L938).
  int sample_window_rows(const params::ParamRegistry& registry) const override {
    return static_cast<int>(registry.get_int("pert_count"));
  }
};

}  // namespace rtsim::platform
