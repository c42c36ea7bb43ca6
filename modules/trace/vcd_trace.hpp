#pragma once
// Signal traces for GTKWave: a thin owner of one SystemC VCD file (sc_create_vcd_trace_file),
// time unit 1 ps, closed in the destructor. Modules register their busy flags
// (sc_signal<bool>) and queue depths (sc_signal<int>) by hierarchical name; SystemC's VCD writer
// turns the dots of a name into nested scopes ("peripheral.pipeline.busy" is signal "busy" in
// scope peripheral/pipeline).
//
// SystemC allows tracing only before the simulation starts: registering after the first
// sc_start is std::logic_error here (SystemC itself would only warn and drop the signal).
// SystemC writes nothing if the file is closed before any simulation cycle ran.
//
// SystemC writes a time step's values only when a later trace cycle runs. close() therefore
// advances a run that ended by starvation (status SC_PAUSED, no pending activity) by one
// time-resolution step (1 ps) before closing, so the last step's changes are in the file; read
// sc_time_stamp() before closing. After sc_stop() SystemC cannot run again and the values of the
// final time step are lost: end runs by starvation (or sc_start(until) past the last change).
#include <filesystem>
#include <string>
#include <systemc>

namespace rtsim::modules {

class VcdTrace {
 public:
  /// Creates PATH (".vcd" is appended when PATH does not end in it, as SystemC does).
  explicit VcdTrace(const std::filesystem::path& path);
  ~VcdTrace();
  VcdTrace(const VcdTrace&) = delete;
  VcdTrace& operator=(const VcdTrace&) = delete;

  /// A module's busy flag, e.g. trace_busy(busy_, name() + std::string(".busy")).
  void trace_busy(const sc_core::sc_signal<bool>& busy, const std::string& hierarchical_name);
  /// A queue's depth (number of entries).
  void trace_queue_depth(const sc_core::sc_signal_in_if<int>& depth,
                         const std::string& hierarchical_name);

  /// The file, for other sc_trace overloads; owned by this object.
  sc_core::sc_trace_file* file() const { return file_; }
  /// The file's path, ".vcd" included.
  const std::filesystem::path& path() const { return path_; }
  /// Closes the file now (idempotent; the destructor calls it). See above: may advance simulated
  /// time by one resolution step.
  void close();

 private:
  void check_can_trace(const std::string& hierarchical_name) const;

  std::filesystem::path path_;
  sc_core::sc_trace_file* file_ = nullptr;
};

}  // namespace rtsim::modules
