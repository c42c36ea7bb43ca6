#include "modules/busy_timeline.hpp"

#include <algorithm>

namespace rtsim::modules {

namespace {
/// ceil(a / b) without overflowing a + b.
std::uint64_t ceil_div(std::uint64_t a, std::uint64_t b) { return a / b + (a % b != 0 ? 1 : 0); }
}  // namespace

void BusyTimeline::merge_pairs() {
  // In place: bin i/2 takes bins i and i+1 (no allocation; this runs once per doubling of
  // the recorded span, on up to kMaxBins bins).
  const std::size_t n = busy_.size();
  for (std::size_t i = 0; i < n; i += 2) busy_[i / 2] = busy_[i] + (i + 1 < n ? busy_[i + 1] : 0);
  busy_.resize((n + 1) / 2);
  width_ *= 2;
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
  if (busy_.empty()) {
    origin_ = first_ = s;
    last_ = e;
  } else if (s < origin_) {
    // Earlier than anything so far: grow the bins to the left by whole bins.
    std::uint64_t k = ceil_div(origin_ - s, width_);
    while (busy_.size() + k > kMaxBins) {
      merge_pairs();
      k = ceil_div(origin_ - s, width_);
    }
    busy_.insert(busy_.begin(), static_cast<std::size_t>(k), 0);
    origin_ -= k * width_;
  }
  first_ = std::min(first_, s);
  last_ = std::max(last_, e);
  while (ceil_div(e - origin_, width_) > kMaxBins) merge_pairs();
  const std::uint64_t a = s - origin_;
  const std::uint64_t b = e - origin_;
  const std::size_t first = static_cast<std::size_t>(a / width_);
  const std::size_t last = static_cast<std::size_t>((b - 1) / width_);
  if (busy_.size() <= last) busy_.resize(last + 1, 0);
  for (std::size_t i = first; i <= last; ++i) {
    const std::uint64_t lo = std::max<std::uint64_t>(a, i * width_);
    const std::uint64_t hi = std::min<std::uint64_t>(b, (i + 1) * width_);
    busy_[i] += hi - lo;
  }
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
  for (std::uint64_t v : busy_) sum += v;
  return sc_core::sc_time::from_value(sum);
}

UtilizationWindows BusyTimeline::windows(const sc_core::sc_time& begin, const sc_core::sc_time& end,
                                         std::size_t n) const {
  UtilizationWindows out;
  const std::uint64_t B = begin.value();
  const std::uint64_t E = end.value();
  if (n == 0 || E <= B) return out;
  const long double window = static_cast<long double>(E - B) / static_cast<long double>(n);
  out.begin_s = begin.to_seconds();
  out.window_s = (end - begin).to_seconds() / static_cast<double>(n);
  std::vector<long double> busy(n, 0.0L);
  for (std::size_t i = 0; i < busy_.size(); ++i) {
    if (busy_[i] == 0) continue;
    // The bin, less what lies outside everything recorded (exact edges for the first and last).
    const std::uint64_t x0 = std::max(origin_ + i * width_, first_);
    const std::uint64_t x1 = std::min(origin_ + (i + 1) * width_, last_);
    const std::uint64_t c0 = std::max(x0, B);
    const std::uint64_t c1 = std::min(x1, E);
    if (c1 <= c0) continue;
    // This bin's busy time per tick, spread evenly over the bin.
    const long double density =
        static_cast<long double>(busy_[i]) / static_cast<long double>(x1 - x0);
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
  }
  out.values.resize(n);
  for (std::size_t j = 0; j < n; ++j) out.values[j] = static_cast<double>(busy[j] / window);
  return out;
}

}  // namespace rtsim::modules
