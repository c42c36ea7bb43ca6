#pragma once
// The traces of one run, as a machine's modules emit them: Perfetto slices and counters
// (transactions on tracks named by module hierarchy) and VCD signals (busy flags, queue
// depths) for GTKWave. Either may be off; every call is then a cheap no-op.
//
// VCD signals are written at the writing thread's synchronisation points, so with a quantum q
// their edges may be up to q late; at quantum 0 (the reference) they are exact.
#include <memory>
#include <string>
#include <systemc>
#include <vector>

#include "modules/trace/perfetto_trace.hpp"
#include "modules/trace/vcd_trace.hpp"
#include "platform/machine.hpp"

namespace rtsim::platform {

class MachineTrace {
 public:
  explicit MachineTrace(const RunOptions& opts);

  bool perfetto_on() const { return perfetto_ != nullptr; }

  /// Elaboration only: a busy flag / a queue depth signal, returning its handle.
  int declare_busy(const std::string& module);
  int declare_depth(const std::string& queue);

  /// Simulation: set a busy flag; set a queue depth (also a Perfetto counter at `t`).
  void busy(int handle, bool value) {
    if (handle >= 0) busy_[static_cast<std::size_t>(handle)]->write(value);
  }
  void depth(int handle, int value, const sc_core::sc_time& t) {
    if (handle >= 0) write_depth(static_cast<std::size_t>(handle), value, t);
  }

  /// A Perfetto slice on the track of `module` (tracks are created on first use).
  void slice(std::string_view module, std::string_view name, const sc_core::sc_time& start,
             const sc_core::sc_time& duration,
             std::initializer_list<modules::PerfettoTrace::Arg> args = {}) {
    if (perfetto_) perfetto_->slice(perfetto_->track(module), name, start, duration, args);
  }

  /// Ends the traces (the VCD file may need one more resolution step: call after sc_start).
  void close();

 private:
  void write_depth(std::size_t h, int value, const sc_core::sc_time& t);
  using DepthSignal = sc_core::sc_signal<int, sc_core::SC_UNCHECKED_WRITERS>;
  std::unique_ptr<modules::PerfettoTrace> perfetto_;
  std::unique_ptr<modules::VcdTrace> vcd_;
  std::vector<std::unique_ptr<sc_core::sc_signal<bool>>> busy_;
  std::vector<std::unique_ptr<DepthSignal>> depth_;
  std::vector<int> depth_track_;
  std::vector<std::string> depth_name_;
};

}  // namespace rtsim::platform
