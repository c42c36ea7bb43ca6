#pragma once
// What shading a region-sample costs a shading node (seed 004 Fig. 9, L134-L152): for every
// shading function the region holds, its pre-light and post-light parts; the common light loop
// once for each light; and each table lookup in proportion to the pixels that need it (190 us
// for all 8K pixels, L148). The times are one node's, one sample's, one region's; Fig. 9 gives
// them with the lookups excluded (L152). So what a region costs comes from what it holds: an
// all-pin region 150 us less the alley's and ball's parts plus 4 lookups (760 us, L150), a
// region of background nothing.
#include <systemc>

#include "firmware/deferred/deferred_shader.hpp"
#include "modules/module_params.hpp"

namespace rtsim::platform::pixelflow {

class ShadingCosts {
 public:
  /// Declares `cost.*` under a shading node's path.
  static void declare_params(const modules::ParamDecls& shader);
  explicit ShadingCosts(const modules::ModuleParams& shader);

  /// The node's time for a region-sample whose shading did `work`.
  sc_core::sc_time time_for(const deferred::RegionWork& work) const;
  /// The parts of it (for the traces): pre- and post-light, the lights, the lookups.
  sc_core::sc_time shading_part(const deferred::RegionWork& work) const;
  sc_core::sc_time lookup_part(const deferred::RegionWork& work) const;

 private:
  sc_core::sc_time crown_, label_, scuffs_, dirt_, pin_phong_, wood_, reflection_, ball_phong_,
      phong_, light_, lookup_;
};

}  // namespace rtsim::platform::pixelflow
