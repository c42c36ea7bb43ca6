#pragma once
// gaudet-pert's termination detection (the thesis does not say how, note 001 §1.6): the initial
// rays whose whole ray tree has been answered, over every ShadeProcessor, against the frame's;
// and each ray's time around its ring. Owned by the machine; every ShadeProcessor reports here,
// so no processor keeps a count for the others.
#include <cstdint>
#include <systemc>

#include "modules/latency_recorder.hpp"
#include "platform/machine.hpp"

namespace rtsim::platform::gaudet {

class FrameProgress {
 public:
  /// A frame of `initial_rays` (the pixel samples simulated in detail); progress to `opts`.
  FrameProgress(std::uint64_t initial_rays, const RunOptions& opts)
      : total_(initial_rays), opts_(opts) {}

  /// An initial ray's whole tree is answered: its pixel sample is finished.
  void tree_done() {
    ++done_;
    if (opts_.progress && (done_ & 1023) == 0) report();
  }
  /// A ray came back to its ShadeProcessor `latency` after it was sent.
  void ray_back(const sc_core::sc_time& latency) { latency_.add(latency); }

  bool complete() const { return done_ == total_; }
  std::uint64_t done() const { return done_; }
  std::uint64_t total() const { return total_; }
  /// Rays around their rings (stats.json ray_latency_s).
  const modules::LatencyRecorder& latency() const { return latency_; }
  /// Tells --progress where the frame is.
  void report() const {
    if (opts_.progress) opts_.progress(static_cast<long>(done_), static_cast<long>(total_));
  }

 private:
  std::uint64_t total_;
  std::uint64_t done_ = 0;
  const RunOptions& opts_;
  modules::LatencyRecorder latency_;
};

}  // namespace rtsim::platform::gaudet
