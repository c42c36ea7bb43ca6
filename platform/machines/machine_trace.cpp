#include "platform/machines/machine_trace.hpp"

namespace rtsim::platform {

MachineTrace::MachineTrace(const RunOptions& opts) {
  if (!opts.perfetto_path.empty())
    perfetto_ =
        std::make_unique<modules::PerfettoTrace>(opts.perfetto_path, opts.perfetto_max_events);
  if (!opts.vcd_path.empty()) vcd_ = std::make_unique<modules::VcdTrace>(opts.vcd_path);
}

int MachineTrace::declare_busy(const std::string& module) {
  if (!vcd_) return -1;
  busy_.push_back(
      std::make_unique<sc_core::sc_signal<bool>>(sc_core::sc_gen_unique_name("busy"), false));
  vcd_->trace_busy(*busy_.back(), module + ".busy");
  return static_cast<int>(busy_.size()) - 1;
}

int MachineTrace::declare_depth(const std::string& queue) {
  if (!vcd_ && !perfetto_) return -1;
  depth_.push_back(std::make_unique<DepthSignal>(sc_core::sc_gen_unique_name("depth"), 0));
  if (vcd_) vcd_->trace_queue_depth(*depth_.back(), queue + ".depth");
  depth_track_.push_back(perfetto_ ? perfetto_->track(queue) : -1);
  depth_name_.push_back("depth");
  return static_cast<int>(depth_.size()) - 1;
}

void MachineTrace::write_depth(std::size_t h, int value, const sc_core::sc_time& t) {
  if (vcd_) depth_[h]->write(value);
  if (perfetto_) perfetto_->counter(depth_track_[h], depth_name_[h], t, value);
}

void MachineTrace::close() {
  if (vcd_) vcd_->close();
  if (perfetto_) perfetto_->close();
}

}  // namespace rtsim::platform
