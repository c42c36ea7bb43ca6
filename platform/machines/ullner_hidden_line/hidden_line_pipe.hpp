#pragma once
// The hidden-line elimination pipeline (seed 000 §3.4, Fig. 3-31, L1723-L1733): for each
// polygon a plane processor a boundary plane (its edges' planes perpendicular to the screen,
// then its own plane, Fig. 3-28) and a cleanup processor (L1791-L1805), idle plane processors
// where the pipe has more than the scene needs, a string of cleanup processors to catch the
// debris (L1799), and one divider at the end (L1765). Segments enter at one end from the host;
// every processor is a PipeStage module on a bit-serial link to the next (L1906), the last's to
// the divider.
//
// The pipe hands the processors' outputs on deepest first (pipe_stage.hpp): after the host hands
// a message to the first processor, each processor with outputs waiting hands one on, and the
// processor that received it hands all its own on before the one behind it goes on. Then a
// processor's link never starts before everything that bounds it is known, and the times are
// those of a simulation that steps every processor in time order.
//
// The in-flight fault point "intersection": `--fault intersection:W:MASK` XORs MASK into t_n of
// the W-th intersection (from 0) the last link carries to the divider.
#include <cstdint>
#include <memory>
#include <systemc>
#include <vector>

#include "firmware/hiddenline/plane.hpp"
#include "modules/latency_probe.hpp"
#include "modules/link.hpp"
#include "modules/module_params.hpp"
#include "modules/statistics.hpp"
#include "platform/machine.hpp"
#include "platform/machines/ullner_hidden_line/divider_node.hpp"
#include "platform/machines/ullner_hidden_line/pipe_stage.hpp"

namespace rtsim::platform {
class MachineRun;
}

namespace rtsim::platform::ullner_hidden_line {

/// A fault on an intersection the last link carries (`--fault intersection:W:MASK`).
struct IntersectionFault {
  std::uint64_t index = 0;
  std::uint32_t xor_mask = 0;
  bool applied = false;
};

/// The pipe's layout: the polygons' processors in the scene's order (hiddenline::build_chain
/// with no trailing ones), then the idle plane processors, then the trailing cleanup ones.
struct PipeLayout {
  std::vector<hiddenline::Stage> polygons;
  std::size_t idle_plane_processors = 0;
  std::size_t trailing_cleanups = 0;
};

class HiddenLinePipe : public sc_core::sc_module, public modules::StatGroup, private LinkWatch {
 public:
  static constexpr const char* kName = "pipe";
  static constexpr const char* kPlaneClass = "pp";
  static constexpr const char* kCleanupClass = "cp";
  static constexpr const char* kFaultPoint = "intersection";
  /// The pipe's own parameters (`pipe.*`) and its processors' classes (`pp.*`, `cp.*`).
  static void declare_params(const modules::ParamDecls& machine);
  /// Plane processors a pipe may have (its processors are modules of the simulation).
  static constexpr std::size_t kMaxPlaneProcessors = 50000;
  /// `pipe.plane_processors` (0: as many as the scene's planes) and `pipe.trailing_cleanups`.
  static std::size_t plane_processors(const params::ParamRegistry& registry);
  static std::size_t trailing_cleanups(const params::ParamRegistry& registry);
  /// `pipe.word_bits` and the links' class parameters.
  static std::uint64_t word_bits(const params::ParamRegistry& registry);

  HiddenLinePipe(sc_core::sc_module_name name, MachineRun& run, PipeLayout layout,
                 std::vector<IntersectionFault> faults);

  /// The first processor (the host sends to its `in`).
  PipeStage& first() { return *stages_.front(); }
  /// Hands on every output waiting in the pipe, deepest first (after the host handed the first
  /// processor a message).
  void drain();

  const std::vector<std::unique_ptr<PipeStage>>& stages() const { return stages_; }
  DividerNode& divider() { return divider_; }
  const DividerNode& divider() const { return divider_; }
  const modules::Link& link_out() const { return link_out_; }
  const std::vector<IntersectionFault>& faults() const { return faults_; }
  std::size_t plane_processors() const { return plane_processors_; }
  std::size_t cleanup_processors() const { return stages_.size() - plane_processors_; }

  /// Latency probe: each segment's journey by its edge number (started by the host).
  void follow(std::vector<modules::LatencyProbe::Journey>* journeys, int pp_stage, int pp_link,
              int cp_stage, int cp_link);
  /// Ends the journeys of the segments that reached the divider and drops the rest (hidden
  /// whole and suppressed on the way).
  void end_journeys();

  /// The processors' accounts, once the frame is over: the counters below.
  void account();

 private:
  void handed(std::size_t index, MessageInFlight& f, const sc_core::sc_time& ready,
              const sc_core::sc_time& start) override;
  void accepted(std::size_t index, const hiddenline::Message& m, const sc_core::sc_time& arrived,
                const sc_core::sc_time& accepted) override;

  modules::LatencyProbe& probe_;
  std::uint64_t word_bits_;
  std::vector<StageState> states_;  ///< the processors' state, in pipe order
  std::vector<std::unique_ptr<PipeStage>> stages_;
  std::size_t plane_processors_ = 0;
  modules::Link link_out_;
  DividerNode divider_;
  std::vector<IntersectionFault> faults_;
  std::uint64_t out_intersections_ = 0;
  std::vector<std::size_t> stack_;
  // The probe's record of each segment: its journey, and when it reached and was accepted by
  // the processor it is at.
  std::vector<modules::LatencyProbe::Journey>* journeys_ = nullptr;
  std::vector<sc_core::sc_time> seg_accepted_;
  int probe_pp_ = -1, probe_pp_link_ = -1, probe_cp_ = -1, probe_cp_link_ = -1;

  modules::Counter multiplications_{*this, "multiplications",
                                    "the plane processors' multiplications: six a segment "
                                    "(L1908), two a comparison"};
  modules::Counter intersections_{*this, "intersections_sent",
                                  "intersection messages handed from one processor to the next"};
  modules::Counter redundant_{*this, "redundant_intersections",
                              "intersections a plane processor dropped as redundant (L1789)"};
  modules::Counter comparisons_{*this, "cleanup_comparisons",
                                "the cleanup processors' cross multiplications (L1912)"};
  modules::Counter suppressed_{*this, "suppressed_segments",
                               "segments a cleanup processor found hidden whole (L1797)"};
  modules::Counter merged_{*this, "merged_parts", "hidden parts merged by a cleanup processor"};
  modules::Counter dropped_{*this, "dropped_parts",
                            "hidden parts a cleanup processor dropped (nothing of [0, 1])"};
  modules::Counter messages_{*this, "messages", "messages handed from one processor to the next"};
  modules::Duration link_busy_{*this, "links_busy_s",
                               "time the processors' links carried bits, summed over them"};
  modules::Duration waited_{*this, "link_waited_s",
                            "time messages waited, ready, for a link or the next register, "
                            "summed over the processors"};
};

}  // namespace rtsim::platform::ullner_hidden_line
