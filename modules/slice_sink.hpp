#pragma once
// Where a module records what it works on as Perfetto slices (a ray in a processor, a packet on
// a bus): the run's traces (platform/machines/machine_trace.hpp) implement it. Kit blocks take
// one so they need not know the platform layer. Used by modules::Processor.
#include <cstdint>
#include <initializer_list>
#include <string_view>
#include <systemc>

#include "modules/trace/perfetto_trace.hpp"

namespace rtsim::modules {

class SliceSink {
 public:
  virtual ~SliceSink() = default;
  /// A slice `name` on the track of `module` (its hierarchical name) from `start` for
  /// `duration`, with numeric arguments.
  virtual void slice(std::string_view module, std::string_view name, const sc_core::sc_time& start,
                     const sc_core::sc_time& duration,
                     std::initializer_list<PerfettoTrace::Arg> args = {}) = 0;
  /// A flow event linking slices (PerfettoTrace::flow) on the track of `module`; none unless
  /// the traces take flows.
  virtual void flow(std::string_view /*module*/, std::string_view /*name*/, std::uint64_t /*id*/,
                    PerfettoTrace::FlowPhase /*phase*/, const sc_core::sc_time& /*t*/) {}
  /// A step of item `id`'s journey through the machine (a ray's, a job's: `flow` names which) on
  /// the track of `module` at `t`: the traces link the item's slices, from module to link to
  /// module, by a flow (its first step starts it). Nothing unless the traces take flows.
  virtual void hop(std::string_view /*module*/, std::string_view /*flow*/, std::uint64_t /*id*/,
                   const sc_core::sc_time& /*t*/) {}
  /// Whether slices go anywhere: a module may skip preparing what it would record. It does not
  /// change over a run (a module may ask once).
  virtual bool records() const { return true; }
};

}  // namespace rtsim::modules
