#pragma once
// The timing of a processor's intersection unit (seed 000 L841-L850, Fig. 2-28): a nine-stage
// pipeline whose four memory-referencing stages share the processor's 16-bit memory.
//   1 the polygon's address (its entry in the subvolume's list; the list's count with the first)
//   2 fetch the parameters of t (n_p, d_p)        3 compute t: no output if it does not exist,
//                                                   is behind the ray or beyond the bound
//   4 compute the intersection point p_r
//   5 fetch the parameters of u                   6 compute u: no output if out of [0, 1]
//   7 fetch the parameters of v                   8 compute v: no output if out of [0, 1]
//   9 keep the closest hit; a new one passes its t back to stage 3 as the bound (L847)
// Each stage holds one polygon; one that is done waits in its stage while the next is full. A
// memory stage's fetch holds the memory, two 16-bit transfers a word; when the memory is free
// it goes to the waiting fetch of the latest stage ("the stages occurring later in the pipeline
// have priority over those appearing earlier ... to prevent the log jams", L850; the other order
// is a parameter, for the ablation). A compute stage takes one stage time.
//
// The answer (which polygon is closest) is the search's own, found with the bound as it stands
// after each test; the pipeline only times it. Its bound comes back from stage 9, so a polygon
// may pass stage 3 on a bound that a hit still in the pipe is about to tighten: its u (and v)
// are fetched for nothing, and the words fetched count them.
#include <cstdint>
#include <span>
#include <systemc>
#include <vector>

namespace rtsim::platform::ullner_array {

/// A polygon test as the pipeline meets it, from the search's intersection (which computes u
/// and v whenever t is in the subvolume's range, whatever the bound then).
struct PipelineTest {
  double t = 0.0;
  bool t_in_range = false;  ///< t exists, is beyond t_min and below `bound` (stage 3's test)
  bool u_valid = false;
  bool v_valid = false;
  /// Stage 3's bound when no hit has come back: the end of the ray's part in this subvolume.
  double bound = 0.0;
  /// The bound had every hit before it come back at once (the search's own): what passes stage
  /// 3 beyond it fetches u and v for nothing.
  double immediate_bound = 0.0;
  /// Its subvolume's list (0, 1, ... in the search's order): one list's hits do not tighten
  /// another's bound.
  std::uint32_t list = 0;
  /// The first polygon of its list (stage 1 fetches the list's count too).
  bool first_of_list = false;
  /// A shadow ray's test: any hit answers, and no bound comes back.
  bool any_hit = false;
};

/// Which waiting fetch the memory serves first.
enum class FetchPriority { kLaterStages, kEarlierStages };

struct PipelineTiming {
  sc_core::sc_time memory_cycle;  ///< one 16-bit transfer
  sc_core::sc_time stage_time;    ///< a compute stage's time
  FetchPriority priority = FetchPriority::kLaterStages;
};

/// What one stream of tests took: the memory is the unit's from `start` on.
struct PipelineRun {
  sc_core::sc_time memory_end;     ///< when its last fetch ended
  sc_core::sc_time done;           ///< when its last polygon left the pipe (the interrupt)
  sc_core::sc_time memory_busy;    ///< time its fetches held the memory
  std::uint64_t words = 0;         ///< words fetched
  std::uint64_t wasted_words = 0;  ///< u and v words fetched on a bound a hit in the pipe tightened
};

/// Words each memory stage fetches (L841): a list entry, then t's 4 (n_p, d_p), u's and v's 8.
inline constexpr std::uint64_t kEntryWords = 1, kTWords = 4, kUWords = 8, kVWords = 8;

/// Runs `tests` through the pipeline in order from `start`.
PipelineRun run_pipeline(std::span<const PipelineTest> tests, const sc_core::sc_time& start,
                         const PipelineTiming& timing);

/// How often run_pipeline looks at the stages at one moment. Once is enough when every compute
/// stage and every fetch takes time (a look starts nothing that ends at that moment, and a stage
/// a look frees is looked at after it, the latest stage first); with a zero time it looks again
/// until nothing changes. kUntilSettled always looks again: the reference that
/// tests/intersection_pipeline_test.cpp holds run_pipeline to.
enum class PipelineLooks { kAsNeeded, kUntilSettled };
PipelineRun run_pipeline(std::span<const PipelineTest> tests, const sc_core::sc_time& start,
                         const PipelineTiming& timing, PipelineLooks looks);

}  // namespace rtsim::platform::ullner_array
