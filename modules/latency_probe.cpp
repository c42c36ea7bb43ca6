#include "modules/latency_probe.hpp"

#include <algorithm>

namespace rtsim::modules {

int LatencyProbe::stage(const std::string& name) {
  for (std::size_t i = 0; i < stages_.size(); ++i)
    if (stages_[i].name == name) return static_cast<int>(i);
  stages_.emplace_back();
  stages_.back().name = name;
  return static_cast<int>(stages_.size() - 1);
}

LatencyProbe::Journey LatencyProbe::begin(const sc_core::sc_time& now) {
  if (!enabled_) return kNoJourney;
  Journey j;
  if (!free_.empty()) {
    j = free_.back();
    free_.pop_back();
  } else {
    j = static_cast<Journey>(slots_.size());
    slots_.emplace_back();
  }
  Slot& s = slots_[j];
  s.begin = now;
  std::fill(s.parts.begin(), s.parts.end(), 0.0);
  return j;
}

LatencyProbe::Journey LatencyProbe::fork(Journey j) {
  if (j == kNoJourney) return kNoJourney;
  const Journey k = begin(slots_[j].begin);
  slots_[k].parts = slots_[j].parts;  // after begin(): it may have grown slots_
  return k;
}

void LatencyProbe::drop(Journey j) {
  if (j != kNoJourney) free_.push_back(j);
}

void LatencyProbe::add(Journey j, int stage, LatencyPart part, const sc_core::sc_time& dt) {
  if (j == kNoJourney) return;
  Slot& s = slots_[j];
  const std::size_t k =
      static_cast<std::size_t>(stage) * kLatencyParts + static_cast<std::size_t>(part);
  if (s.parts.size() <= k) s.parts.resize(stages_.size() * kLatencyParts, 0.0);
  s.parts[k] += dt.to_seconds();
}

void LatencyProbe::end(Journey j, const sc_core::sc_time& now) {
  if (j == kNoJourney) return;
  Slot& s = slots_[j];
  const double e2e = (now - s.begin).to_seconds();
  end_to_end_.add_seconds(e2e);
  double attributed = 0.0;
  for (std::size_t st = 0; st < stages_.size(); ++st) {
    double total = 0.0;
    for (int p = 0; p < kLatencyParts; ++p) {
      const std::size_t k = st * kLatencyParts + static_cast<std::size_t>(p);
      const double v = k < s.parts.size() ? s.parts[k] : 0.0;
      stages_[st].parts[p] += v;
      total += v;
    }
    stages_[st].total.add_seconds(total);
    attributed += total;
  }
  unattributed_ += e2e - attributed;
  ++rays_;
  free_.push_back(j);
}

UnitSchema LatencyProbe::units() {
  UnitSchema u{{"rays", StatUnit::count},
               {"unattributed_s", StatUnit::seconds},
               {"stages.*.share", StatUnit::fraction},
               {"stages.*_s", StatUnit::seconds}};
  u.add(LatencyRecorder::units(), "end_to_end_s.");
  return u;
}

nlohmann::ordered_json LatencyProbe::to_json() const {
  nlohmann::ordered_json j;
  j["rays"] = rays_;
  j["unit"] = unit_;
  if (!scope_.empty()) j["scope"] = scope_;
  j["end_to_end_s"] = end_to_end_.to_json();
  const long double n = rays_ > 0 ? static_cast<long double>(rays_) : 1.0L;
  const double mean_e2e = j["end_to_end_s"]["mean"].get<double>();
  j["unattributed_s"] = static_cast<double>(unattributed_ / n);
  nlohmann::ordered_json stages = nlohmann::ordered_json::object();
  static constexpr const char* kNames[kLatencyParts] = {"queueing_s", "service_s", "transfer_s"};
  for (const StageTotals& st : stages_) {
    nlohmann::ordered_json s;
    long double total = 0;
    for (int p = 0; p < kLatencyParts; ++p) {
      s[kNames[p]] = static_cast<double>(st.parts[p] / n);
      total += st.parts[p];
    }
    s["total_s"] = static_cast<double>(total / n);
    s["p99_s"] = st.total.percentile(0.99);
    s["share"] = mean_e2e > 0 ? static_cast<double>(total / n) / mean_e2e : 0.0;
    stages[st.name] = std::move(s);
  }
  j["stages"] = std::move(stages);
  return j;
}

}  // namespace rtsim::modules
