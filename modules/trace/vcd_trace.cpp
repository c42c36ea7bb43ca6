#include "modules/trace/vcd_trace.hpp"

#include <sysc/tracing/sc_tracing_ids.h>

#include <stdexcept>

namespace rtsim::modules {

namespace {

/// The VCD time unit: SystemC's default time resolution, so every simulated time is exact.
constexpr double kVcdTimeUnitPs = 1.0;

}  // namespace

VcdTrace::VcdTrace(const std::filesystem::path& path) {
  std::filesystem::path stem = path;
  if (stem.extension() == ".vcd") stem.replace_extension();
  path_ = stem;
  path_ += ".vcd";
  // sc_create_vcd_trace_file appends ".vcd" itself.
  file_ = sc_core::sc_create_vcd_trace_file(stem.string().c_str());
  if (file_ == nullptr) throw std::runtime_error("cannot create VCD trace " + path_.string());
  // SystemC reports every time-unit change as an info message; the unit is fixed here, so the
  // message only adds noise to every traced run.
  sc_core::sc_report_handler::set_actions(sc_core::SC_ID_TRACING_TIMESCALE_UNIT_, sc_core::SC_INFO,
                                          sc_core::SC_DO_NOTHING);
  file_->set_time_unit(kVcdTimeUnitPs, sc_core::SC_PS);
}

VcdTrace::~VcdTrace() { close(); }

void VcdTrace::close() {
  if (file_ == nullptr) return;
  // SystemC's VCD writer emits a time step's values only when a later trace cycle runs, so the
  // last step of a run that ended by starvation (sc_start() returning with nothing pending)
  // would be missing: a busy flag that falls at the end of the frame would stay high in
  // GTKWave. One more time-resolution step, with nothing left to run, writes it.
  if (sc_core::sc_get_status() == sc_core::SC_PAUSED && !sc_core::sc_pending_activity()) {
    sc_core::sc_start(sc_core::sc_get_time_resolution());
  }
  sc_core::sc_close_vcd_trace_file(file_);
  file_ = nullptr;
}

void VcdTrace::check_can_trace(const std::string& hierarchical_name) const {
  if (file_ == nullptr) {
    throw std::logic_error("VcdTrace: " + hierarchical_name + " traced after close()");
  }
  // SystemC initialises trace files at the first simulation cycle; until then (elaboration and
  // the start_of_simulation callbacks) signals may be added.
  const auto status = sc_core::sc_get_status();
  const bool elaborating = status == sc_core::SC_UNITIALIZED || status == sc_core::SC_ELABORATION ||
                           status == sc_core::SC_BEFORE_END_OF_ELABORATION ||
                           status == sc_core::SC_END_OF_ELABORATION ||
                           status == sc_core::SC_START_OF_SIMULATION;
  if (!elaborating) {
    throw std::logic_error("VcdTrace: " + hierarchical_name +
                           " traced after the simulation started; register signals before "
                           "sc_start");
  }
  if (hierarchical_name.empty()) throw std::invalid_argument("VcdTrace: empty signal name");
}

void VcdTrace::trace_busy(const sc_core::sc_signal<bool>& busy,
                          const std::string& hierarchical_name) {
  check_can_trace(hierarchical_name);
  sc_core::sc_trace(file_, busy, hierarchical_name);
}

void VcdTrace::trace_queue_depth(const sc_core::sc_signal_in_if<int>& depth,
                                 const std::string& hierarchical_name) {
  check_can_trace(hierarchical_name);
  sc_core::sc_trace(file_, depth, hierarchical_name);
}

}  // namespace rtsim::modules
