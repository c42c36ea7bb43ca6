#pragma once
// pxpl5-raytrace: ray tracing on Pixel-Planes 5 with VOL2's organisation (seed 004 L259-L452):
// a host, a master GP handing out screen regions, i860 ray-caster GPs with the whole scene,
// compositor GPs owning bands of rows, SIMD renderers owning 128 x 128 tiles and a frame buffer,
// all on the kit's 5 Gbit/s token ring (L284).
#include "platform/machine.hpp"

namespace rtsim::platform {

class Pxpl5Raytrace final : public Machine {
 public:
  std::string name() const override { return "pxpl5-raytrace"; }
  std::string description() const override {
    return "Ray tracing on Pixel-Planes 5 (VOL2's organisation): a master GP handing out screen "
           "regions to i860 ray casters, compositors, SIMD renderers and a frame buffer on a "
           "5 Gbit/s token ring (seed 004)";
  }
  std::string sample_scene() const override;
  void declare_params(params::ParamRegistry& registry) const override;
  FunctionalTwin make_twin(scenes::Scene& scene,
                           const params::ParamRegistry& registry) const override;
  RunResult run(scenes::Scene& scene, FunctionalTwin& twin, const params::ParamRegistry& registry,
                const RunOptions& opts) const override;
  /// Its casters sample screen regions on a lattice handed out by the master GP, not rows of
  /// vision rays: a sampled run's windows are regions (FrameSample::of_units).
  int sample_units(const params::ParamRegistry& registry, int width, int height) const override;
  /// Its estimate rests on each region's busy time, which does not grow as queues fill.
  int sample_warmup_rays(const params::ParamRegistry&) const override { return 0; }
};

}  // namespace rtsim::platform
