#include "platform/machines/machine_trace.hpp"

#include <algorithm>
#include <filesystem>
#include <vector>

#include "modules/sim_time.hpp"
#include "modules/stat_directory.hpp"

namespace rtsim::platform {

namespace {

double seconds_of(std::uint64_t ticks) {
  return sc_core::sc_time::from_value(static_cast<sc_core::sc_time::value_type>(ticks))
      .to_seconds();
}

sc_core::sc_time time_of(std::uint64_t ticks) {
  return sc_core::sc_time::from_value(static_cast<sc_core::sc_time::value_type>(ticks));
}

constexpr const char* kDepth = "depth";

struct Signal {
  std::string module;  ///< stats.json name
  std::string what;    ///< "busy", "depth", or another level signal's name
  std::vector<modules::LevelChange> changes;
};

}  // namespace

MachineTrace::MachineTrace(const RunOptions& opts)
    : filter_(opts.trace_filter),
      max_events_(opts.trace_max_events),
      too_large_(opts.trace_too_large) {
  if (!opts.perfetto_path.empty()) {
    perfetto_ = std::make_unique<modules::PerfettoTrace>(opts.perfetto_path, max_events_);
    // Streamed while the run goes on: the user hears of a trace too large to open while there
    // is still time to stop it.
    if (too_large_)
      perfetto_->on_size(modules::kTraceWarnBytes,
                         [this, name = opts.perfetto_path.filename().string()](std::uint64_t b) {
                           too_large_(name, b, modules::sim_now().to_seconds());
                         });
  }
  if (!opts.vcd_path.empty()) vcd_ = std::make_unique<modules::VcdTrace>(opts.vcd_path);
  if (on()) keep_intervals_.emplace();
}

MachineTrace::~MachineTrace() {
  if (perfetto_) perfetto_->abandon();
  if (vcd_) vcd_->abandon();
}

bool MachineTrace::keeps(std::string_view module, const sc_core::sc_time& start,
                         const sc_core::sc_time& duration) {
  if (!filter_.keeps_time(start.value(), duration.value())) return false;
  if (filter_.modules.empty()) return true;
  auto it = module_kept_.find(module);
  if (it == module_kept_.end())
    it = module_kept_.emplace(std::string(module), filter_.keeps_module(module)).first;
  return it->second;
}

void MachineTrace::hop(std::string_view module, std::string_view flow, std::uint64_t id,
                       const sc_core::sc_time& t) {
  if (!perfetto_ || !keeps(module, t, sc_core::SC_ZERO_TIME)) return;
  auto it = flows_started_.find(flow);
  if (it == flows_started_.end()) it = flows_started_.emplace(std::string(flow), 0).first;
  const bool first = it->second.insert(id).second;
  perfetto_->flow(
      perfetto_->track(module), flow, id,
      first ? modules::PerfettoTrace::FlowPhase::kStart : modules::PerfettoTrace::FlowPhase::kStep,
      t);
}

modules::UnitSchema MachineTrace::units() {
  using modules::StatUnit;
  return {{"window_s", StatUnit::seconds},
          {"stats_interval_s", StatUnit::seconds},
          {"requested_window_s", StatUnit::seconds},
          {"max_events", StatUnit::count},
          {"signals", StatUnit::count},
          {"perfetto.events_written", StatUnit::count},
          {"perfetto.events_dropped", StatUnit::count},
          {"perfetto.counters_dropped", StatUnit::count},
          {"perfetto.bytes", StatUnit::bytes},
          {"vcd.changes_written", StatUnit::count},
          {"vcd.changes_dropped", StatUnit::count},
          {"vcd.bytes", StatUnit::bytes}};
}

nlohmann::ordered_json MachineTrace::finish(const modules::StatWindow& window) {
  if (!on()) return nullptr;
  // The signals, from the sources of stats.json's numbers, by stats.json's names.
  std::vector<Signal> signals;
  std::uint64_t last = window.end.value();
  for (modules::NamedSignal& s : modules::StatDirectory::instance().signals(
           [this](const std::string& name) { return filter_.keeps_module(name); }))
    signals.push_back({std::move(s.name), std::move(s.kind), std::move(s.changes)});
  for (const Signal& s : signals)
    if (!s.changes.empty()) last = std::max(last, s.changes.back().t);
  // What the traces cover: the window asked for, else from time 0 to the end of the frame (or
  // of the last change, if a module was still busy after it).
  const std::uint64_t from = std::min(filter_.from, last);
  const std::uint64_t to = std::max(from, std::min(filter_.to, last));

  if (perfetto_) {
    for (const Signal& s : signals) {
      const int track = perfetto_->track(s.module);
      // The value at `from`, every change after it up to `to`, and the value at `to`, so the
      // counter is drawn (and integrates) over the whole window.
      long level = 0;
      std::size_t i = 0;
      for (; i < s.changes.size() && s.changes[i].t <= from; ++i) level = s.changes[i].level;
      perfetto_->counter(track, s.what, time_of(from), static_cast<double>(level));
      for (; i < s.changes.size() && s.changes[i].t <= to; ++i) {
        level = s.changes[i].level;
        perfetto_->counter(track, s.what, time_of(s.changes[i].t), static_cast<double>(level));
      }
      if (to > from) perfetto_->counter(track, s.what, time_of(to), static_cast<double>(level));
    }
    const auto pair = [](double a, double b) { return nlohmann::json::array({a, b}).dump(); };
    // The window it holds whole (up to the earliest event its cap dropped).
    perfetto_->other_data(
        "rtsim_window_s",
        pair(seconds_of(from),
             std::max(seconds_of(from), std::min(seconds_of(to), perfetto_->first_dropped_s()))));
    perfetto_->other_data("rtsim_stats_interval_s",
                          pair(window.begin.to_seconds(), window.end.to_seconds()));
    perfetto_->other_data("rtsim_modules", nlohmann::json(filter_.modules).dump());
  }
  if (vcd_) {
    // Its size before it is written: a value change is a line of about 16 bytes (a time stamp,
    // or a value and an identifier).
    if (too_large_) {
      std::uint64_t changes = 0;
      for (const Signal& s : signals) changes += s.changes.size();
      if (max_events_ != 0) changes = std::min<std::uint64_t>(changes, max_events_);
      if (changes * kVcdBytesPerChange > modules::kTraceWarnBytes)
        too_large_(vcd_->path().filename().string(), changes * kVcdBytesPerChange, -1.0);
    }
    for (Signal& s : signals) {
      std::string name = s.module;  // appends: see vcd_trace.cpp on GCC 12's -Wrestrict
      name += '.';
      name += s.what;
      vcd_->signal(
          name, std::move(s.changes),
          s.what == kDepth ? modules::VcdTrace::Kind::kCount : modules::VcdTrace::Kind::kLevel);
    }
    vcd_->close(from, to, max_events_);
  }
  if (perfetto_) perfetto_->close();

  // What the traces hold whole: the window, up to the earliest event a cap dropped.
  double kept_to = seconds_of(to);
  if (perfetto_) kept_to = std::min(kept_to, perfetto_->first_dropped_s());
  if (vcd_ && vcd_->changes_dropped() > 0)
    kept_to = std::min(kept_to, seconds_of(std::max(from, vcd_->first_dropped())));
  kept_to = std::max(kept_to, seconds_of(from));
  nlohmann::ordered_json j;
  j["window_s"] = {seconds_of(from), kept_to};
  if (kept_to < seconds_of(to)) j["requested_window_s"] = {seconds_of(from), seconds_of(to)};
  j["stats_interval_s"] = {window.begin.to_seconds(), window.end.to_seconds()};
  j["modules"] = filter_.modules;
  j["max_events"] = max_events_;
  j["signals"] = signals.size();
  const auto bytes_of = [](const std::filesystem::path& p) -> std::uint64_t {
    std::error_code ec;
    const auto n = std::filesystem::file_size(p, ec);
    return ec ? 0 : static_cast<std::uint64_t>(n);
  };
  if (perfetto_)
    j["perfetto"] = {{"file", perfetto_->path().filename().string()},
                     {"events_written", perfetto_->events_written()},
                     {"events_dropped", perfetto_->events_dropped()},
                     {"counters_dropped", perfetto_->counters_dropped()},
                     {"bytes", bytes_of(perfetto_->path())}};
  if (vcd_)
    j["vcd"] = {{"file", vcd_->path().filename().string()},
                {"changes_written", vcd_->changes_written()},
                {"changes_dropped", vcd_->changes_dropped()},
                {"bytes", bytes_of(vcd_->path())}};
  return j;
}

}  // namespace rtsim::platform
