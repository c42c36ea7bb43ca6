#include "modules/busy_timeline.hpp"

#include <algorithm>
#include <limits>
#include <type_traits>

#include "modules/sim_time.hpp"

namespace rtsim::modules {

namespace {

constexpr std::uint64_t kNarrowMax = std::numeric_limits<std::uint32_t>::max();

/// Calls f(i, ticks) for each bin i that [a, b) (relative to bin 0's start) falls in, with the
/// ticks that fall in it.
template <class F>
void for_each_bin_of(std::uint64_t a, std::uint64_t b, unsigned shift, F&& f) {
  const std::size_t first = static_cast<std::size_t>(a >> shift);
  const std::size_t last = static_cast<std::size_t>((b - 1) >> shift);
  if (first == last) {  // the common case: an interval within one bin
    f(first, b - a);
    return;
  }
  for (std::size_t i = first; i <= last; ++i) {
    const std::uint64_t lo = std::max<std::uint64_t>(a, std::uint64_t{i} << shift);
    const std::uint64_t hi = std::min<std::uint64_t>(b, std::uint64_t{i + 1} << shift);
    f(i, hi - lo);
  }
}

/// Whether 32-bit bins can take [a, b) without a bin passing 2^32 - 1.
bool fits(const std::vector<std::uint32_t>& busy, std::uint64_t a, std::uint64_t b,
          unsigned shift) {
  bool fit = true;
  for_each_bin_of(a, b, shift, [&](std::size_t i, std::uint64_t ticks) {
    fit = fit && ticks <= kNarrowMax - busy[i];
  });
  return fit;
}

}  // namespace

void BusyTimeline::widen() {
  wide_bins_.reserve(kMaxBins);
  wide_bins_.assign(bins_.begin(), bins_.end());
  std::vector<std::uint32_t>().swap(bins_);
  wide_ = true;
}

void BusyTimeline::merge_pairs() {
  // In place: bin i/2 takes bins i and i+1 (no allocation; this runs once per doubling of
  // the recorded span, on up to kMaxBins bins). 32-bit bins whose pair would not fit widen
  // first.
  if (!wide_) {
    for (std::size_t i = 0; i + 1 < bins_.size(); i += 2)
      if (std::uint64_t{bins_[i]} + bins_[i + 1] > kNarrowMax) {
        widen();
        break;
      }
  }
  with_bins([](auto& busy) {
    const std::size_t n = busy.size();
    for (std::size_t i = 0; i < n; i += 2) busy[i / 2] = busy[i] + (i + 1 < n ? busy[i + 1] : 0);
    busy.resize((n + 1) / 2);
  });
  ++shift_;
}

void BusyTimeline::add(const sc_core::sc_time& start, const sc_core::sc_time& duration) {
  const std::uint64_t s = start.value();
  const std::uint64_t d = duration.value();
  if (d == 0) return;
  const std::uint64_t e = s + d;
  if (keep_) {
    if (!intervals_.empty() && intervals_.back().end == s)
      intervals_.back().end = e;
    else
      intervals_.push_back({s, e});
  }
  const bool first = !recorded_;
  first_ = first ? s : std::min(first_, s);
  last_ = first ? e : std::max(last_, e);
  recorded_ = true;
  if (binned_) {
    // An interval that starts where the one before ended extends it; the bins take it when the
    // next does not, or when they are read (settle). Adding [a, c) once puts every tick in the
    // bin [a, b) and [b, c) would have put it in: the bins' width and origin depend only on the
    // earliest start and latest end added, and merging pairs keeps each bin's ticks.
    if (pending_.end == s && pending_.end > pending_.start) {
      pending_.end = e;
      return;
    }
    settle_pending();
    pending_ = {s, e};
    return;
  }
  if (first) {
    open_ = {s, e};
  } else if (open_.end == s) {
    open_.end = e;
  } else {
    sparse_.push_back(open_);
    open_ = {s, e};
    // Intervals held: sparse_ and open_.
    if (sparse_.size() + 1 > kSparseIntervals) to_bins();
  }
}

void BusyTimeline::to_bins() {
  // Bins for the span so far with room to double once before the first merge.
  shift_ = 0;
  while (bins_for(last_ - first_) > kMaxBins / 2) ++shift_;
  origin_ = first_;
  // Room for every bin it may have (64 KiB): the bins grow with the span, a few at a time, and
  // growing a vector by doubling copied them and left the blocks they outgrew behind.
  with_bins([](auto& busy) {
    busy.reserve(kMaxBins);
    busy.assign(1, 0);
  });
  binned_ = true;
  for (const Interval& i : sparse_) add_to_bins(i.start, i.end);
  add_to_bins(open_.start, open_.end);
  std::vector<Interval>().swap(sparse_);
}

void BusyTimeline::add_to_bins(std::uint64_t s, std::uint64_t e) {
  if (s < origin_) {
    // Earlier than anything so far: grow the bins to the left by whole bins.
    std::uint64_t k = bins_for(origin_ - s);
    while (bin_count() + k > kMaxBins) {
      merge_pairs();
      k = bins_for(origin_ - s);
    }
    with_bins([k](auto& busy) { busy.insert(busy.begin(), static_cast<std::size_t>(k), 0); });
    origin_ -= k << shift_;
  }
  while (bins_for(e - origin_) > kMaxBins) merge_pairs();
  const std::uint64_t a = s - origin_;
  const std::uint64_t b = e - origin_;
  const std::size_t last = static_cast<std::size_t>((b - 1) >> shift_);
  if (bin_count() <= last) with_bins([last](auto& busy) { busy.resize(last + 1, 0); });
  if (!wide_ && !fits(bins_, a, b, shift_)) widen();
  with_bins([&](auto& busy) {
    using T = typename std::decay_t<decltype(busy)>::value_type;
    for_each_bin_of(a, b, shift_,
                    [&](std::size_t i, std::uint64_t ticks) { busy[i] += static_cast<T>(ticks); });
  });
}

void BusyTimeline::settle_pending() {
  if (pending_.end <= pending_.start) return;
  add_to_bins(pending_.start, pending_.end);
  pending_ = {0, 0};
}

void BusyTimeline::settle() const {
  // The timelines are members of modules, never const objects themselves: a reader that finds
  // an interval still pending hands it to the bins (each timeline is read by one thread).
  const_cast<BusyTimeline*>(this)->settle_pending();
}

std::vector<LevelChange> BusyTimeline::level_changes() const {
  std::vector<std::uint64_t> starts, ends;
  starts.reserve(intervals_.size());
  ends.reserve(intervals_.size());
  for (const Interval& i : intervals_) {
    starts.push_back(i.start);
    ends.push_back(i.end);
  }
  std::sort(starts.begin(), starts.end());
  std::sort(ends.begin(), ends.end());
  return modules::level_changes(starts, ends);
}

sc_core::sc_time BusyTimeline::total() const {
  std::uint64_t sum = 0;
  with_bins([&sum](const auto& busy) {
    for (std::uint64_t v : busy) sum += v;
  });
  sum += pending_.end - pending_.start;
  for (const Interval& i : sparse_) sum += i.end - i.start;
  if (recorded_ && !binned_) sum += open_.end - open_.start;
  return from_ticks(sum);
}

UtilizationWindows BusyTimeline::windows(const sc_core::sc_time& begin, const sc_core::sc_time& end,
                                         std::size_t n) const {
  UtilizationWindows out;
  const std::uint64_t B = begin.value();
  const std::uint64_t E = end.value();
  if (n == 0 || E <= B) return out;
  settle();
  const long double window = static_cast<long double>(E - B) / static_cast<long double>(n);
  out.begin_s = begin.to_seconds();
  out.window_s = (end - begin).to_seconds() / static_cast<double>(n);
  std::vector<long double> busy(n, 0.0L);
  // Spreads `ticks` of busy time evenly over [x0, x1) into the windows it overlaps.
  const auto spread = [&](std::uint64_t ticks, std::uint64_t x0, std::uint64_t x1) {
    const std::uint64_t c0 = std::max(x0, B);
    const std::uint64_t c1 = std::min(x1, E);
    if (c1 <= c0) return;
    const long double density = static_cast<long double>(ticks) / static_cast<long double>(x1 - x0);
    const long double r0 = static_cast<long double>(c0 - B);
    const long double r1 = static_cast<long double>(c1 - B);
    auto j = static_cast<std::size_t>(r0 / window);
    for (; j < n; ++j) {
      const long double w0 = window * static_cast<long double>(j);
      const long double w1 = j + 1 == n ? static_cast<long double>(E - B) : w0 + window;
      const long double lo = std::max(r0, w0);
      const long double hi = std::min(r1, w1);
      if (hi > lo) busy[j] += density * (hi - lo);
      if (w1 >= r1) break;
    }
  };
  // Sparse: each interval exactly.
  for (const Interval& i : sparse_) spread(i.end - i.start, i.start, i.end);
  if (recorded_ && !binned_) spread(open_.end - open_.start, open_.start, open_.end);
  with_bins([&](const auto& bins) {
    for (std::size_t i = 0; i < bins.size(); ++i) {
      if (bins[i] == 0) continue;
      // The bin, less what lies outside everything recorded (exact edges for the first and
      // last).
      const std::uint64_t x0 = std::max(origin_ + (std::uint64_t{i} << shift_), first_);
      const std::uint64_t x1 = std::min(origin_ + (std::uint64_t{i + 1} << shift_), last_);
      if (x1 <= x0) continue;
      spread(bins[i], x0, x1);
    }
  });
  out.values.resize(n);
  for (std::size_t j = 0; j < n; ++j) out.values[j] = static_cast<double>(busy[j] / window);
  return out;
}

}  // namespace rtsim::modules
