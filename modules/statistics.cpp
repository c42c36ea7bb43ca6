#include "modules/statistics.hpp"

#include <mutex>
#include <set>
#include <stdexcept>
#include <tuple>

#include "modules/stat_directory.hpp"

namespace rtsim::modules {

/// Utilisation windows a frame is cut into: enough to see phases (fill, steady state, drain) in
/// a plot, few enough to keep stats.json small (assumption, not a seed figure).
static constexpr std::size_t kUtilizationWindows = 100;

StatGroup::StatGroup(std::string path) : path_(std::move(path)) {
  StatDirectory::instance().add(*this);
}

StatGroup::StatGroup(const StatGroup& parent, std::string_view child)
    : StatGroup(parent.stat_path().empty() ? std::string(child)
                                           : parent.stat_path() + "." + std::string(child)) {}

StatGroup::~StatGroup() { StatDirectory::instance().remove(*this); }

Statistic::Statistic(StatGroup& group, std::string name, std::string description, StatUnit unit)
    : label_(&intern(std::move(name), std::move(description), unit)) {
  group.statistics_.push_back(this);
}

const Statistic::Label& Statistic::intern(std::string name, std::string description,
                                          StatUnit unit) {
  // Labels live as long as the process: a machine's statistics have a bounded set of them (the
  // names are relative to their groups), however many instances.
  const auto key = [](const Label& l) { return std::tie(l.name, l.description, l.unit); };
  const auto less = [key](const Label& a, const Label& b) { return key(a) < key(b); };
  static std::mutex mutex;
  static std::set<Label, decltype(less)> labels(less);
  const std::lock_guard<std::mutex> lock(mutex);
  return *labels.insert(Label{std::move(name), std::move(description), unit}).first;
}

void Counter::report(StatReport& out, const StatWindow& /*window*/) const {
  out.values[name()] = value_;
  declare_unit(out, name());
}

void CounterArray::report(StatReport& out, const StatWindow& /*window*/) const {
  for (std::size_t k = 0; k < kinds_.size(); ++k) {
    out.values[name() + kinds_[k]] = values_[k];
    declare_unit(out, name() + kinds_[k]);
  }
}

void Peak::report(StatReport& out, const StatWindow& /*window*/) const {
  out.values[name()] = value_;
  declare_unit(out, name());
}

void Scalar::report(StatReport& out, const StatWindow& /*window*/) const {
  out.values[name()] = value_;
  declare_unit(out, name());
}

void Duration::report(StatReport& out, const StatWindow& /*window*/) const {
  out.values[name()] = value_.to_seconds();
  declare_unit(out, name());
}

void Busy::report(StatReport& out, const StatWindow& window) const {
  // One busy time a name: two would add, and their windows would overwrite each other.
  if (out.busy_reported)
    throw std::logic_error("two Busy statistics report under one name (" + name() + ")");
  out.busy_reported = true;
  out.busy = total_;
  out.units.emplace_back("busy_s", StatUnit::seconds);
  out.units.emplace_back("utilization", StatUnit::fraction);
  const UtilizationWindows w = timeline_.windows(window.begin, window.end, kUtilizationWindows);
  if (!w.values.empty()) {
    out.windows = {{"begin_s", w.begin_s}, {"window_s", w.window_s}, {"values", w.values}};
    out.units.emplace_back("utilization_windows.begin_s", StatUnit::seconds);
    out.units.emplace_back("utilization_windows.window_s", StatUnit::seconds);
    out.units.emplace_back("utilization_windows.values", StatUnit::fraction);
  }
}

void Busy::signals(std::vector<TraceSignal>& out) const {
  if (timeline_.keeps_intervals()) out.push_back({"busy", timeline_.level_changes()});
}

void Level::report(StatReport& out, const StatWindow& window) const {
  if (!out.queue.is_null())
    throw std::logic_error("two Level statistics report under one name (" + name() + ")");
  const Occupancy::Summary s = occupancy_.summarize(window.begin, window.end);
  out.queue = {{"capacity", capacity_ == kUnbounded ? nlohmann::ordered_json(nullptr)
                                                    : nlohmann::ordered_json(capacity_)},
               {"mean_occupancy", s.mean},
               {"max_occupancy", s.max}};
  out.units.emplace_back("queue.capacity", StatUnit::count);
  out.units.emplace_back("queue.mean_occupancy", StatUnit::ratio);
  out.units.emplace_back("queue.max_occupancy", StatUnit::count);
}

void Level::signals(std::vector<TraceSignal>& out) const {
  out.push_back({"depth", occupancy_.depth_changes()});
}

void Distribution::report(StatReport& out, const StatWindow& /*window*/) const {
  out.values[name()] = recorder_.to_json();
  static const UnitSchema kUnits = LatencyRecorder::units();
  for (const auto& [key, unit] : kUnits.entries()) out.units.emplace_back(name() + "." + key, unit);
}

void Computed::report(StatReport& out, const StatWindow& /*window*/) const {
  nlohmann::ordered_json v = value_();
  // Each number of an object in this unit, under its key; an array's numbers under its name.
  if (v.is_object()) {
    for (const auto& [k, x] : v.items())
      if (!x.is_structured()) declare_unit(out, name() + "." + k);
  } else {
    declare_unit(out, name());
  }
  out.values[name()] = std::move(v);
}

void LevelSignal::signals(std::vector<TraceSignal>& out) const {
  out.push_back({name(), changes_});
}

}  // namespace rtsim::modules
