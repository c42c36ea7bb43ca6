#pragma once
// The frame sequencer: the video timing of the scan-line tree (seed 000 L1350-L1352, L1551). At
// each frame's start — the first when the T&C array's first version is done, then every
// `pcp.frame_rate` period — it has every scan conversion processor scan out the latest version
// its memory holds: a new one if the T&C array finished it by then, else the last one again (a
// re-scan, L1352: "the same transformed and clipped polygons ... scan converted more than
// once"). A version first on the screen lets the array begin the next (its memories are free:
// the scan converters keep their own copy, L1350). The run ends with the first frame that shows
// the last version, whose image is the run's.
#include <tlm_utils/simple_initiator_socket.h>

#include <memory>
#include <systemc>
#include <vector>

#include "modules/module_params.hpp"
#include "modules/processor.hpp"
#include "platform/machines/ullner_scanline_tree/tc_array.hpp"

namespace rtsim::platform {
class MachineRun;
}

namespace rtsim::platform::ullner_scanline_tree {

class FrameSequencer : public modules::Processor {
 public:
  static constexpr const char* kName = "frames";

  SC_HAS_PROCESS(FrameSequencer);
  /// `leaves` scan converters (idle ones past the polygons); frames `period` apart.
  FrameSequencer(sc_core::sc_module_name name, MachineRun& run, TcArray& tc, std::size_t leaves,
                 std::size_t polygons, int versions, const sc_core::sc_time& period);

  /// Scan converter k's queue (bound before the simulation).
  std::vector<std::unique_ptr<tlm_utils::simple_initiator_socket<FrameSequencer>>> to_scp;

  /// Frame f's start (the first frame's: the first version's end).
  sc_core::sc_time frame_start(std::size_t f) const {
    return first_ + period_ * static_cast<double>(f);
  }
  /// Frames begun; the version each showed.
  const std::vector<int>& shown() const { return shown_; }
  /// Frames that showed a version again (its polygons re-scanned).
  std::uint64_t rescans() const { return rescans_.value(); }

 private:
  void run();

  TcArray& tc_;
  std::size_t leaves_, polygons_;
  int versions_;
  sc_core::sc_time period_;
  sc_core::sc_time first_ = sc_core::SC_ZERO_TIME;
  std::vector<int> shown_;
  modules::Counter frames_{*this, "frames_shown", "frames begun"};
  modules::Counter rescans_{*this, "rescans", "frames that showed the last version again"};
};

}  // namespace rtsim::platform::ullner_scanline_tree
