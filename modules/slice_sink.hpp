#pragma once
// Where a module records what it works on as Perfetto slices (a ray in a processor, a packet on
// a bus): the run's traces (platform/machines/machine_trace.hpp) implement it. Kit blocks take
// one so they need not know the platform layer. Used by modules::Processor.
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
};

}  // namespace rtsim::modules
