#include "modules/latency_recorder.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>

namespace rtsim::modules {

namespace {
/// Nearest-rank percentile of `s` by selection (no full sort: runs record millions of rays);
/// reorders `s`.
double nearest_rank(std::vector<double>& s, double p) {
  const std::size_t rank = static_cast<std::size_t>(std::ceil(p * static_cast<double>(s.size())));
  const std::size_t k = std::min(s.size() - 1, rank == 0 ? 0 : rank - 1);
  std::nth_element(s.begin(), s.begin() + static_cast<std::ptrdiff_t>(k), s.end());
  return s[k];
}
}  // namespace

double LatencyRecorder::percentile(double p) const {
  if (samples_.empty()) return 0.0;
  std::vector<double> s = samples_;
  return nearest_rank(s, p);
}

UnitSchema LatencyRecorder::units() {
  return {{"count", StatUnit::count},           {"mean", StatUnit::seconds},
          {"p50", StatUnit::seconds},           {"p99", StatUnit::seconds},
          {"max", StatUnit::seconds},           {"histogram.edges_s", StatUnit::seconds},
          {"histogram.counts", StatUnit::count}};
}

nlohmann::ordered_json LatencyRecorder::to_json() const {
  nlohmann::ordered_json j;
  j["count"] = samples_.size();
  if (samples_.empty()) {
    j["mean"] = j["p50"] = j["p99"] = j["max"] = 0.0;
    return j;
  }
  std::vector<double> s = samples_;
  long double sum = 0;
  double lo = s.front(), hi = s.front();
  for (double v : s) {
    sum += v;
    lo = std::min(lo, v);
    hi = std::max(hi, v);
  }
  auto pct = [&s](double p) { return nearest_rank(s, p); };
  j["mean"] = static_cast<double>(sum / static_cast<long double>(s.size()));
  j["p50"] = pct(0.50);
  j["p99"] = pct(0.99);
  j["max"] = hi;
  // Histogram: 4 buckets per octave from the smallest positive sample.
  lo = std::max(lo, 1e-12);
  hi = std::max(hi, lo);
  const int buckets = std::max(1, static_cast<int>(std::ceil(4.0 * std::log2(hi / lo))) + 1);
  std::vector<double> edges(static_cast<std::size_t>(buckets) + 1);
  for (int b = 0; b <= buckets; ++b) edges[static_cast<std::size_t>(b)] = lo * std::exp2(b / 4.0);
  std::vector<std::uint64_t> counts(static_cast<std::size_t>(buckets), 0);
  for (double v : s) {
    const auto b =
        static_cast<std::size_t>(std::upper_bound(edges.begin(), edges.end(), v) - edges.begin());
    counts[std::min(counts.size() - 1, b == 0 ? 0 : b - 1)]++;
  }
  j["histogram"] = {{"edges_s", edges}, {"counts", counts}};
  return j;
}

}  // namespace rtsim::modules
