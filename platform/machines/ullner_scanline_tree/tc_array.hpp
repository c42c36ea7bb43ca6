#pragma once
// The T&C processors on their shared bus (seed 000 §3.3.1, L1096-L1336): one processor a
// polygon, the program broadcast from the bus's end and executed in lockstep (SIMD, L1100-
// L1102), so the array takes the program's length times the instruction time (6-7 us, L1276,
// L1334) whatever its size, plus the instructions a frame spends on moving objects (L1336).
//
// A run of several frames has a version of the scene a frame (the camera turned between
// them): the array transforms version v once version v - 1 is on the screen — while the scan
// converters scan v - 1 out of their own memories (L1350) — and puts it in `versions` when done.
// The frame sequencer (frame_sequencer.hpp) hands the scan converters the latest version at
// every frame's start.
#include <functional>
#include <memory>
#include <systemc>
#include <vector>

#include "firmware/scanline/tc_frame.hpp"
#include "firmware/scanline/tc_program.hpp"
#include "modules/module_params.hpp"
#include "modules/processor.hpp"
#include "modules/timed_fifo.hpp"

namespace rtsim::platform {
class MachineRun;
}

namespace rtsim::platform::ullner_scanline_tree {

class TcArray : public modules::Processor {
 public:
  static constexpr const char* kName = "tc";
  static void declare_params(const modules::ParamDecls& tc);
  /// Its parameters, read before it is built (the frames a run will show).
  static sc_core::sc_time instruction_time(const params::ParamRegistry& registry);
  static std::uint64_t motion_instructions(const params::ParamRegistry& registry);

  SC_HAS_PROCESS(TcArray);
  /// Version v of the scene as the host loads it (its view's literals, its polygons' normals
  /// turned to that view's eye): valid until the next call.
  using Loader = std::function<const scanline::TcFrame&(int v)>;
  /// `versions` versions (one for a single frame), each loaded by `load` when its turn comes.
  TcArray(sc_core::sc_module_name name, MachineRun& run, int versions, Loader load);

  /// A transformed version (its index) when its broadcast ended, for the frame sequencer.
  modules::TimedFifo<int> versions;
  /// From the frame sequencer: version v first on the screen (its index), so v + 1 may begin.
  modules::TimedFifo<int> shown;

  /// Version v's edge chains, polygon by polygon (ready once v is in `versions`, until
  /// released).
  const std::vector<scanline::EdgeChains>& chains(int v) const {
    return chains_[static_cast<std::size_t>(v)];
  }
  /// Version v is off the screen for good: its chains are dropped (a run of many versions keeps
  /// two at most).
  void release(int v) {
    std::vector<scanline::EdgeChains>().swap(chains_[static_cast<std::size_t>(v)]);
  }
  /// When the first version's broadcast ended: the first frame's start.
  sc_core::sc_time done() const { return done_; }
  const scanline::BroadcastProgram& program() const { return program_; }
  sc_core::sc_time instruction_time() const { return instruction_time_; }
  /// Instructions broadcast a frame: the program and the motion's.
  std::uint64_t instructions_a_version() const { return program_.total() + motion_; }

 private:
  void run();

  modules::ModuleParams params_;
  MachineRun& run_;
  Loader load_;
  scanline::BroadcastProgram program_;
  sc_core::sc_time instruction_time_;
  std::uint64_t motion_;
  sc_core::sc_time done_ = sc_core::SC_ZERO_TIME;
  std::vector<std::vector<scanline::EdgeChains>> chains_;
  modules::Counter instructions_{*this, "instructions", "instructions broadcast"};
  modules::Counter executed_{*this, "executed",
                             "instructions the processors executed (not shut down), summed"};
  modules::Counter polygons_out_{*this, "polygons_out",
                                 "polygons left with an edge list after clipping, summed over "
                                 "the versions"};
};

}  // namespace rtsim::platform::ullner_scanline_tree
