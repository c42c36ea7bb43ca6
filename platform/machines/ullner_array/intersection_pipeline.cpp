#include "platform/machines/ullner_array/intersection_pipeline.hpp"

#include <array>
#include <limits>
#include <stdexcept>

#include "modules/sim_time.hpp"

namespace rtsim::platform::ullner_array {

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
  return run_pipeline(tests, start, timing, PipelineLooks::kAsNeeded);
}

PipelineRun run_pipeline(std::span<const PipelineTest> tests, const sc_core::sc_time& start,
                         const PipelineTiming& timing, PipelineLooks looks) {
  PipelineRun out;
  out.memory_end = start;
  out.done = start;
  if (tests.empty()) return out;
  // In ticks (sc_time values) throughout: a processor runs this for every subvolume it
  // searches, and it was a tenth of a large array's run in sc_time.
  using Ticks = std::uint64_t;
  const auto add = [](Ticks a, Ticks b) {
    Ticks sum = 0;
    if (__builtin_add_overflow(a, b, &sum)) modules::time_overflow();
    return sum;
  };
  const Ticks stage_time = timing.stage_time.value();
  // A fetch holds the memory two 16-bit transfers a word.
  const auto fetch_time = [&](std::uint64_t words) {
    return modules::times(timing.memory_cycle, 2 * words).value();
  };
  const Ticks entry_time = fetch_time(kEntryWords), first_entry_time = fetch_time(kEntryWords + 1),
              t_time = fetch_time(kTWords), u_time = fetch_time(kUWords),
              v_time = fetch_time(kVWords);
  const std::size_t n = tests.size();
  struct Slot {
    std::size_t item = 0;
    bool started = false;  ///< its stage's work (a fetch, a computation) has begun
    bool wasted = false;   ///< it passed stage 3 only on a bound still on its way back
    int passes = -1;  ///< stage 3: whether t passed, decided when it was computed (-1: not yet)
    Ticks ready = 0;
  };
  std::array<Slot, kStages> stage{};
  // Bit s: stage s holds a polygon. The passes below visit only these (a stream of a few
  // polygons leaves most of the nine stages empty most of the time).
  unsigned full = 0;
  const auto holds = [&](int s) { return (full >> s & 1u) != 0; };
  // The bound stage 9 passed back, and the list it belongs to.
  double fed_back = std::numeric_limits<double>::infinity();
  std::uint32_t fed_back_list = 0;
  bool any_fed_back = false;
  std::size_t issued = 0, left = 0;
  Ticks now = start.value(), memory_free = start.value(), memory_busy = 0, done = now,
        memory_end = now;
  const std::array<int, 4> later_first{kFetchV, kFetchU, kFetchT, kAddress};
  const std::array<int, 4> earlier_first{kAddress, kFetchT, kFetchU, kFetchV};
  const auto& order = timing.priority == FetchPriority::kLaterStages ? later_first : earlier_first;
  // One look a moment when nothing a look starts can end at that moment (PipelineLooks): about
  // half of this function's work went into second looks that found nothing to do.
  const bool look_again =
      looks == PipelineLooks::kUntilSettled || stage_time == 0 || entry_time == 0;

  while (left < n) {
    bool progress = true;
    while (progress) {
      progress = false;
      // Done polygons move on, the latest stage first (so that each finds the room the one
      // ahead of it has just left), or leave: no output at 3, 6 or 8, or kept at 9. A polygon
      // moved on in this pass is not visited again in it (its new stage is later).
      for (unsigned visit = full; visit != 0;) {
        const int s = 31 - __builtin_clz(visit);
        visit &= ~(1u << s);
        Slot& here = stage[static_cast<std::size_t>(s)];
        if (!here.started || here.ready > now) continue;
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
          full &= ~(1u << s);
          ++left;
          done = now;
          progress = true;
          continue;
        }
        if (holds(s + 1)) continue;  // it waits in its stage
        Slot& next = stage[static_cast<std::size_t>(s + 1)];
        next = Slot{
            .item = here.item, .started = false, .wasted = here.wasted, .passes = -1, .ready = now};
        if (!is_fetch(s + 1)) {
          next.started = true;
          next.ready = add(now, stage_time);
        }
        full = (full & ~(1u << s)) | (1u << (s + 1));
        progress = true;
      }
      // The next polygon enters stage 1.
      if (!holds(kAddress) && issued < n) {
        stage[kAddress] = Slot{.item = issued++, .started = false, .passes = -1, .ready = now};
        full |= 1u << kAddress;
        progress = true;
      }
      // A free memory goes to the waiting fetch of highest priority.
      if (memory_free <= now) {
        for (const int s : order) {
          Slot& f = stage[static_cast<std::size_t>(s)];
          if (!holds(s) || f.started) continue;
          const PipelineTest& T = tests[f.item];
          const std::uint64_t words = s == kAddress  ? kEntryWords + (T.first_of_list ? 1 : 0)
                                      : s == kFetchT ? kTWords
                                      : s == kFetchU ? kUWords
                                                     : kVWords;
          const Ticks d = s == kAddress  ? (T.first_of_list ? first_entry_time : entry_time)
                          : s == kFetchT ? t_time
                          : s == kFetchU ? u_time
                                         : v_time;
          f.started = true;
          f.ready = add(now, d);
          memory_free = f.ready;
          memory_end = memory_free;
          memory_busy = add(memory_busy, d);
          out.words += words;
          if ((s == kFetchU || s == kFetchV) && f.wasted) out.wasted_words += words;
          progress = true;
          break;
        }
      }
      if (!look_again) break;
    }
    if (left == n) break;
    // The next thing to happen: a stage's work ending, or the memory coming free for a fetch.
    Ticks next = 0;
    bool any = false, waiting = false;
    for (unsigned visit = full; visit != 0; visit &= visit - 1) {
      const Slot& s = stage[static_cast<std::size_t>(__builtin_ctz(visit))];
      if (s.started && s.ready > now && (!any || s.ready < next)) {
        next = s.ready;
        any = true;
      }
      if (!s.started) waiting = true;
    }
    if (waiting && memory_free > now && (!any || memory_free < next)) {
      next = memory_free;
      any = true;
    }
    if (!any) throw std::logic_error("ullner-array: the intersection pipeline stalled");
    now = next;
  }
  out.memory_end = modules::from_ticks(memory_end);
  out.done = modules::from_ticks(done);
  out.memory_busy = modules::from_ticks(memory_busy);
  return out;
}

}  // namespace rtsim::platform::ullner_array
