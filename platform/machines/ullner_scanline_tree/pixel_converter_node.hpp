#pragma once
// The pixel conversion processor at the root (seed 000 §3.3.4, L1521-L1547): it takes the root's
// segments and paints their pixels as the video beam passes them, background where no segment
// covers (firmware/scanline/pixel_converter.hpp). With `video.paced` the beam sweeps line y from
// T0 + y t_line, T0 when the scan-out begins (the T&C broadcast's end) and t_line a 30th of a
// second over the lines (L1551: 65 us at 512 lines): a segment that reaches it after the beam
// has passed its first pixel is late, and its line misses its time (L1551-L1553). Unpaced, it
// paints as fast as its pixel time allows, to measure what the tree can deliver.
//
// A split root has one processor a strip (L1596), each painting its strip's pixels into the
// frame's rows; the "faster hardware" composing the strips into one video stream is ideal here:
// a line is late if any strip's segment is.
#include <systemc>
#include <vector>

#include "firmware/scanline/pixel_converter.hpp"
#include "firmware/scanline/tc_frame.hpp"
#include "firmware/scanline/tree_frame.hpp"
#include "modules/latency_probe.hpp"
#include "modules/message_channel.hpp"
#include "modules/module_params.hpp"
#include "modules/processor.hpp"
#include "platform/machines/machine_support.hpp"
#include "platform/machines/ullner_scanline_tree/tree_messages.hpp"

namespace rtsim::platform {
class MachineRun;
}

namespace rtsim::platform::ullner_scanline_tree {

class FrameSequencer;

/// A corrupted word on the link into the pixel conversion processor (--fault root:WORD:XOR):
/// WORD counts the root's segments' words in the order they arrive, 11 a segment.
struct RootFault {
  std::uint64_t word = 0;
  std::uint64_t xor_mask = 0;
  bool applied = false;
};

class PixelConverterNode : public modules::Processor {
 public:
  static constexpr const char* kName = "pcp";
  static constexpr const char* kFaultPoint = "root";
  static void declare_params(const modules::ParamDecls& pcp);
  /// Its frame rate parameter (the frame sequencer's period).
  static const modules::FrequencyParam& frame_rate();

  SC_HAS_PROCESS(PixelConverterNode);
  /// The processor of `strip`, painting into `rows` (the frame's, shared by the strips).
  PixelConverterNode(sc_core::sc_module_name name, MachineRun& run, const FrameSequencer& frames,
                     std::vector<scanline::PixelRow>& rows, const scanline::Strip& strip,
                     std::vector<RootFault> faults, const ProbeStages& stages);

  modules::MessageQueue<SegmentMessage> in;

  /// Frames whose stream it has painted to the dummy (fewer than the frames begun after the
  /// run: the tree above it deadlocked).
  std::size_t frames_done() const { return per_line_.size() - (open_ ? 1 : 0); }
  /// When the last frame it finished ended: the last line's time (paced), or its last pixel.
  sc_core::sc_time frame_end() const { return frame_end_; }
  /// Pixels painted from segments.
  std::uint64_t pixels() const { return pixels_.value(); }
  /// Frame f's segments on line y; whether line y of frame f missed its time here.
  std::uint32_t segments_on(std::size_t f, std::size_t y) const { return per_line_[f][y]; }
  bool line_late(std::size_t f, std::size_t y) const { return line_late_[f][y] != 0; }
  const std::vector<RootFault>& faults() const { return faults_; }
  sc_core::sc_time line_time() const { return line_time_; }
  bool paced() const { return paced_; }

 private:
  void run();
  /// Its strip's pixels back to the background, for a new frame.
  void clear_strip();

  modules::ModuleParams params_;
  MachineRun& run_;
  const FrameSequencer& frames_;
  std::vector<scanline::PixelRow>& rows_;
  scanline::Strip strip_;
  bool open_ = false;  ///< a frame begun and not finished
  std::vector<RootFault> faults_;
  modules::LatencyProbe& probe_;
  ProbeStages stages_;
  bool paced_;
  std::uint64_t ahead_;
  sc_core::sc_time pixel_time_, line_time_;
  sc_core::sc_time begin_ = sc_core::SC_ZERO_TIME, frame_end_ = sc_core::SC_ZERO_TIME;
  std::vector<std::vector<std::uint32_t>> per_line_;  ///< by frame, by line
  std::vector<std::vector<char>> line_late_;
  std::uint64_t words_seen_ = 0;
  modules::Counter segments_{*this, "segments", "segments painted"};
  modules::Counter pixels_{*this, "pixels", "pixels painted from segments"};
  modules::Counter late_{*this, "late_segments",
                         "segments that arrived after the beam had passed their first pixel"};
  modules::Duration lateness_{*this, "lateness_s", "how long after the beam they arrived, summed"};
};

}  // namespace rtsim::platform::ullner_scanline_tree
