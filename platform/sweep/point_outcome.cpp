#include "platform/sweep/point_outcome.hpp"

#include <unistd.h>

#include <fstream>
#include <sstream>
#include <stdexcept>

#include "platform/runs/run_queue.hpp"
#include "platform/sweep/stats_document.hpp"

namespace rtsim::sweep {

namespace fs = std::filesystem;

namespace {

// Lines of a failed run's log quoted in its error (rtsim prints one line per error).
constexpr int kLogLinesInError = 3;

std::optional<std::string> read_text(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) return std::nullopt;
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

// The log's last lines on one line, joined by " | ".
std::string one_line(const std::string& text) {
  std::string out;
  std::istringstream in(text);
  std::string line;
  while (std::getline(in, line)) {
    while (!line.empty() && (line.back() == '\r' || line.back() == ' ')) line.pop_back();
    if (line.empty()) continue;
    if (!out.empty()) out += " | ";
    out += line;
  }
  return out;
}

}  // namespace

nlohmann::json PointOutcome::to_json() const {
  return {{"ok", ok},       {"exit_code", exit_code}, {"wall_s", wall_s},
          {"error", error}, {"stats", stats_text},    {"reused", reused}};
}

PointOutcome PointOutcome::from_json(const nlohmann::json& j) {
  PointOutcome o;
  o.ok = j.at("ok").get<bool>();
  o.exit_code = j.at("exit_code").get<int>();
  o.wall_s = j.at("wall_s").get<double>();
  o.error = j.at("error").get<std::string>();
  o.stats_text = j.at("stats").get<std::string>();
  o.reused = j.at("reused").get<bool>();
  return o;
}

PointOutcome outcome_of(const runs::RunOutcome& run) {
  PointOutcome o;
  o.exit_code = run.exit_code;
  o.wall_s = run.wall_s;
  if (run.exit_code != 0) {
    o.error = run.status.empty() ? run.failure : run.status;
    if (run.status == "did not start") o.error += ": " + run.failure;
    const std::string tail = one_line(runs::tail_of_file(run.log, kLogLinesInError));
    if (!tail.empty()) o.error += ": " + tail;
    return o;
  }
  const auto stats = read_text(run.out_dir / "stats.json");
  if (!stats) {
    o.error = "exit status 0 but no stats.json";
    return o;
  }
  if (const std::string problem = stats_json_problem(*stats); !problem.empty()) {
    o.error = "exit status 0 but its stats.json is not one: " + problem;
    return o;
  }
  o.ok = true;
  o.stats_text = *stats;
  return o;
}

void write_file_atomically(const fs::path& path, const std::string& text) {
  // The process id keeps two writers (two MPI ranks on a shared folder) off each other's file.
  const fs::path tmp = path.string() + ".partial-" + std::to_string(::getpid());
  {
    std::ofstream out(tmp, std::ios::binary);
    out << text;
    if (!out) throw std::runtime_error("cannot write " + tmp.string());
  }
  fs::rename(tmp, path);
}

void write_marker(const fs::path& dir, const Point& point, const PointOutcome& o) {
  nlohmann::ordered_json m;
  m["hash"] = point.hash();
  m["command"] = point.command_line();
  m["wall_time_s"] = o.wall_s;
  write_file_atomically(dir / kMarkerFile, m.dump(2) + "\n");
}

std::optional<PointOutcome> find_done(const fs::path& dir, const Point& point) {
  const auto marker = read_text(dir / kMarkerFile);
  if (!marker) return std::nullopt;
  PointOutcome o;
  try {
    const auto m = nlohmann::json::parse(*marker);
    if (m.at("hash").get<std::string>() != point.hash()) return std::nullopt;
    o.wall_s = m.at("wall_time_s").get<double>();
  } catch (const nlohmann::json::exception&) {
    return std::nullopt;  // a damaged marker: run the point again
  }
  const auto stats = read_text(dir / "stats.json");
  if (!stats) return std::nullopt;
  // Anything but a stats.json rtsim could have written (damaged, replaced by hand): run again.
  if (!stats_json_problem(*stats).empty()) return std::nullopt;
  o.ok = true;
  o.exit_code = 0;
  o.stats_text = *stats;
  o.reused = true;
  return o;
}

}  // namespace rtsim::sweep
