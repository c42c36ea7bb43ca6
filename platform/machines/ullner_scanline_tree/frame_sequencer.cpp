#include "platform/machines/ullner_scanline_tree/frame_sequencer.hpp"

#include "modules/message_channel.hpp"
#include "platform/machines/machine_run.hpp"
#include "platform/machines/ullner_scanline_tree/tree_messages.hpp"

namespace rtsim::platform::ullner_scanline_tree {

FrameSequencer::FrameSequencer(sc_core::sc_module_name name, MachineRun& run, TcArray& tc,
                               std::size_t leaves, std::size_t polygons, int versions,
                               const sc_core::sc_time& period)
    : modules::Processor(name, run.trace()),
      tc_(tc),
      leaves_(leaves),
      polygons_(polygons),
      versions_(versions),
      period_(period) {
  for (std::size_t k = 0; k < leaves_; ++k)
    to_scp.push_back(std::make_unique<tlm_utils::simple_initiator_socket<FrameSequencer>>(
        ("to_scp" + std::to_string(k)).c_str()));
  SC_THREAD(run);
}

void FrameSequencer::run() {
  // The first frame starts when the first version is done.
  modules::wait_for_item(tc_.versions, clock_);
  sc_core::sc_time taken;
  int current = tc_.versions.get(clock_.now(), taken);
  clock_.catch_up(taken);
  first_ = clock_.now();
  bool fresh = true;
  for (std::size_t f = 0;; ++f) {
    const sc_core::sc_time start = frame_start(f);
    if (start > clock_.now()) idle_until(start, Wait::kWork);
    if (f > 0) {
      // A version done by the frame's start replaces the one on the screen.
      fresh = tc_.versions.has_item_by(start);
      if (fresh) {
        tc_.release(current);
        current = tc_.versions.get(start, taken);
        clock_.catch_up(taken);
      } else {
        ++rescans_;
      }
    }
    shown_.push_back(current);
    ++frames_;
    if (fresh && current + 1 < versions_) tc_.shown.put(current, clock_.now());
    const auto& chains = tc_.chains(current);
    for (std::size_t k = 0; k < leaves_; ++k) {
      ChainsMessage m;
      if (k < polygons_) m.chains = chains[k];
      modules::send_message(*to_scp[k], m, clock_.now(), m.bits());
    }
    if (current + 1 >= versions_) break;
  }
  clock_.sync();
}

}  // namespace rtsim::platform::ullner_scanline_tree
