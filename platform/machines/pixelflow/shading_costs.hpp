#pragma once
// What shading a region-sample costs a shading node. Two models, `cost.model`:
// - "parts" (the default): Fig. 9's measured times (seed 004 L134-L146) for every shading
//   function the region holds, its pre-light and post-light parts, and the common light loop
//   once for each light. Fig. 9 gives them for one node, one sample, one region, lookups
//   excluded (L152).
// - "instructions": the SIMD instructions the shading programs issue for the same parts
//   (firmware/deferred/shading_programs.*), each at Fig. 6's time (L5-L13, the `simd.*`
//   parameters), plus the surface point every covered region needs first.
// Either way each table lookup costs in proportion to the pixels that need it (190 us for all
// 8K pixels, L148), and what a region costs comes from what it holds: an all-pin region 150 us
// less the alley's and ball's parts plus 4 lookups (760 us, L150), a region of background
// nothing.
#include <systemc>

#include "firmware/deferred/deferred_shader.hpp"
#include "firmware/deferred/shading_programs.hpp"
#include "firmware/deferred/simd_stream.hpp"
#include "modules/module_params.hpp"

namespace rtsim::platform::pixelflow {

class ShadingCosts {
 public:
  /// Declares `cost.*` and `simd.*` under a shading node's path.
  static void declare_params(const modules::ParamDecls& shader);
  ShadingCosts(const modules::ModuleParams& shader, const deferred::ProgramUniforms& uniforms);

  /// The node's time for a region-sample whose shading did `work`, in its two parts: pre- and
  /// post-light with the lights, and the lookups.
  sc_core::sc_time shading_part(const deferred::RegionWork& work) const;
  sc_core::sc_time lookup_part(const deferred::RegionWork& work) const;

  /// The shading programs and Fig. 6's times, whichever model times the node.
  const deferred::ShadingPrograms& programs() const { return programs_; }
  const deferred::simd::InstructionTimes& instruction_times() const { return times_; }

 private:
  sc_core::sc_time fig9_part(const deferred::RegionWork& work) const;

  sc_core::sc_time crown_, label_, scuffs_, dirt_, pin_phong_, wood_, reflection_, ball_phong_,
      phong_, light_, lookup_;
  bool instructions_ = false;
  deferred::simd::InstructionTimes times_;
  deferred::ShadingPrograms programs_;
};

}  // namespace rtsim::platform::pixelflow
