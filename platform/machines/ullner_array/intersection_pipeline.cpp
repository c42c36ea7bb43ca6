#include "platform/machines/ullner_array/intersection_pipeline.hpp"

#include <array>
#include <limits>
#include <optional>
#include <stdexcept>

#include "modules/sim_time.hpp"

namespace rtsim::platform::ullner_array {

using modules::plus;

namespace {

constexpr int kStages = 9;
// Fig. 2-28's stages, from 0: the address, t's fetch, t, p_r, u's fetch, u, v's fetch, v, the
// closest hit.
constexpr int kAddress = 0, kFetchT = 1, kComputeT = 2, kFetchU = 4, kComputeU = 5, kFetchV = 6,
              kComputeV = 7, kClosest = 8;

bool is_fetch(int stage) {
  return stage == kAddress || stage == kFetchT || stage == kFetchU || stage == kFetchV;
}

}  // namespace

PipelineRun run_pipeline(std::span<const PipelineTest> tests, const sc_core::sc_time& start,
                         const PipelineTiming& timing) {
  PipelineRun out;
  out.memory_end = start;
  out.done = start;
  if (tests.empty()) return out;
  const std::size_t n = tests.size();
  struct Slot {
    std::size_t item = 0;
    bool full = false;
    bool started = false;  ///< its stage's work (a fetch, a computation) has begun
    sc_core::sc_time ready;
    int passes = -1;      ///< stage 3: whether t passed, decided when it was computed (-1: not yet)
    bool wasted = false;  ///< it passed stage 3 only on a bound still on its way back
  };
  std::array<Slot, kStages> stage{};
  // The bound stage 9 passed back, and the list it belongs to.
  double fed_back = std::numeric_limits<double>::infinity();
  std::uint32_t fed_back_list = 0;
  bool any_fed_back = false;
  std::size_t issued = 0, left = 0;
  sc_core::sc_time now = start, memory_free = start;
  const std::array<int, 4> later_first{kFetchV, kFetchU, kFetchT, kAddress};
  const std::array<int, 4> earlier_first{kAddress, kFetchT, kFetchU, kFetchV};
  const auto& order = timing.priority == FetchPriority::kLaterStages ? later_first : earlier_first;

  while (left < n) {
    bool progress = true;
    while (progress) {
      progress = false;
      // Done polygons move on, the latest stage first (so that each finds the room the one
      // ahead of it has just left), or leave: no output at 3, 6 or 8, or kept at 9.
      for (int s = kStages - 1; s >= 0; --s) {
        Slot& here = stage[static_cast<std::size_t>(s)];
        if (!here.full || !here.started || here.ready > now) continue;
        const PipelineTest& T = tests[here.item];
        bool leaves = false;
        if (s == kComputeT) {
          if (here.passes < 0) {
            double bound = T.bound;
            if (any_fed_back && fed_back_list == T.list && fed_back < bound) bound = fed_back;
            here.passes = T.t_in_range && T.t < bound ? 1 : 0;
            here.wasted = here.passes && !(T.t < T.immediate_bound);
          }
          leaves = here.passes == 0;
        } else if (s == kComputeU) {
          leaves = !T.u_valid;
        } else if (s == kComputeV) {
          leaves = !T.v_valid;
        } else if (s == kClosest) {
          // A hit: its t is the bound stage 3 tests the list's next polygons against (L847).
          if (!T.any_hit && (!any_fed_back || fed_back_list != T.list || T.t < fed_back)) {
            fed_back = T.t;
            fed_back_list = T.list;
            any_fed_back = true;
          }
          leaves = true;
        }
        if (leaves) {
          here = Slot{};
          ++left;
          out.done = now;
          progress = true;
          continue;
        }
        Slot& next = stage[static_cast<std::size_t>(s + 1)];
        if (next.full) continue;  // it waits in its stage
        next = Slot{.item = here.item,
                    .full = true,
                    .started = false,
                    .ready = now,
                    .passes = -1,
                    .wasted = here.wasted};
        if (!is_fetch(s + 1)) {
          next.started = true;
          next.ready = plus(now, timing.stage_time);
        }
        here = Slot{};
        progress = true;
      }
      // The next polygon enters stage 1.
      Slot& first = stage[kAddress];
      if (!first.full && issued < n) {
        first = Slot{.item = issued++,
                     .full = true,
                     .started = false,
                     .ready = now,
                     .passes = -1,
                     .wasted = false};
        progress = true;
      }
      // A free memory goes to the waiting fetch of highest priority.
      if (memory_free <= now) {
        for (const int s : order) {
          Slot& f = stage[static_cast<std::size_t>(s)];
          if (!f.full || f.started) continue;
          const PipelineTest& T = tests[f.item];
          std::uint64_t words = s == kAddress  ? kEntryWords + (T.first_of_list ? 1 : 0)
                                : s == kFetchT ? kTWords
                                : s == kFetchU ? kUWords
                                               : kVWords;
          const sc_core::sc_time d = modules::times(timing.memory_cycle, 2 * words);
          f.started = true;
          f.ready = plus(now, d);
          memory_free = f.ready;
          out.memory_end = memory_free;
          out.memory_busy = plus(out.memory_busy, d);
          out.words += words;
          if ((s == kFetchU || s == kFetchV) && f.wasted) out.wasted_words += words;
          progress = true;
          break;
        }
      }
    }
    if (left == n) break;
    // The next thing to happen: a stage's work ending, or the memory coming free for a fetch.
    std::optional<sc_core::sc_time> next;
    bool waiting = false;
    for (const Slot& s : stage) {
      if (!s.full) continue;
      if (s.started && s.ready > now && (!next || s.ready < *next)) next = s.ready;
      if (!s.started) waiting = true;
    }
    if (waiting && memory_free > now && (!next || memory_free < *next)) next = memory_free;
    if (!next) throw std::logic_error("ullner-array: the intersection pipeline stalled");
    now = *next;
  }
  return out;
}

}  // namespace rtsim::platform::ullner_array
