#include "app/sample_pilot.hpp"

#include <unistd.h>

#include <cerrno>
#include <charconv>
#include <chrono>
#include <cmath>
#include <cstring>
#include <stdexcept>

#include "app/interrupt_cleanup.hpp"
#include "common/end_with_parent.hpp"
#include "common/input_error.hpp"
#include "common/spawn_logged.hpp"
#include "platform/machines/frame_sample.hpp"

namespace rtsim::app {

double parse_sample_error(const std::string& text) {
  std::string t = text;
  while (!t.empty() && t.back() == ' ') t.pop_back();
  const bool percent = !t.empty() && t.back() == '%';
  if (percent) t.pop_back();
  while (!t.empty() && t.back() == ' ') t.pop_back();
  double v = 0;
  const auto [p, ec] = std::from_chars(t.data(), t.data() + t.size(), v);
  if (t.empty() || ec != std::errc() || p != t.data() + t.size() || !std::isfinite(v))
    throw InputError("--sample-error " + text, 0,
                     "expected a target error: a percentage (\"1%\") or a fraction (\"0.01\")");
  if (percent) v /= 100.0;
  if (!(v > 0.0) || v > 0.5)
    throw InputError("--sample-error " + text, 0,
                     "the target must lie in (0, 50%]: the half-width of the frame time's 99.7% "
                     "interval, relative");
  return v;
}

modules::UnitSchema SamplePlan::units() {
  using modules::StatUnit;
  return {
      {"target_error", StatUnit::fraction},     {"pilot_every", StatUnit::count},
      {"pilot_estimate_s", StatUnit::seconds},  {"pilot_half_width_relative", StatUnit::fraction},
      {"pilot_wall_time_s", StatUnit::seconds}, {"every", StatUnit::count}};
}

SamplePlan plan_sample(const platform::Machine& machine, scenes::Scene& scene,
                       platform::FunctionalTwin& twin, const params::ParamRegistry& registry,
                       const platform::RunOptions& opts, int units, double target) {
  const int windows = platform::FrameSample::windows_in(units, opts.sample_window_rows);
  platform::RunOptions pilot = opts;
  pilot.sample_every = platform::FrameSample::pilot_every(windows);
  pilot.sample_pilot = true;
  pilot.vcd_path.clear();
  pilot.perfetto_path.clear();
  pilot.progress = nullptr;
  pilot.latency_probe = false;
  if (windows < 6)
    throw InputError("--sample-error", 0,
                     "the frame has " + std::to_string(windows) + " windows of " +
                         std::to_string(opts.sample_window_rows) +
                         " rows (or the machine's units of work) each: a pilot and a sample need "
                         "at least 6; a larger image or a smaller --sample-window");

  int fds[2];
  if (::pipe(fds) != 0) throw std::runtime_error(std::string("pipe: ") + std::strerror(errno));
  const auto start = std::chrono::steady_clock::now();
  const pid_t parent = ::getpid();
  const pid_t pid = ::fork();
  if (pid < 0) throw std::runtime_error(std::string("fork: ") + std::strerror(errno));
  if (pid == 0) {
    // The child: its own simulation, its estimate down the pipe, and nothing else; it ends
    // with the run that started it (SIGTERM to the run would otherwise leave it running).
    end_with_parent(parent);
    ::close(fds[0]);
    restart_interrupt_cleanup_after_fork();
    // 'J' and the estimate, or 'E' and the message of bad input (the parent reports it as its
    // own), or 'F' and what failed.
    // (Appends, not `literal + std::string&&`: GCC bug 105651, see InputError.)
    std::string text;
    int code = 0;
    try {
      const auto result = machine.run(scene, twin, registry, pilot);
      text = 'J';
      text += result.stats.value("sample", nlohmann::ordered_json()).dump();
    } catch (const InputError& e) {
      text = 'E';
      text += e.file();
      text += '\n';
      text += std::to_string(e.line());
      text += '\n';
      text += e.message();
      code = 2;
    } catch (const std::exception& e) {
      text = 'F';
      text += e.what();
      code = 1;
    }
    std::size_t sent = 0;
    while (sent < text.size()) {
      const ssize_t w = ::write(fds[1], text.data() + sent, text.size() - sent);
      if (w < 0 && errno == EINTR) continue;
      if (w <= 0) break;
      sent += static_cast<std::size_t>(w);
    }
    ::close(fds[1]);
    ::_exit(sent == text.size() ? code : 1);
  }
  ::close(fds[1]);
  std::string text;
  char buffer[4096];
  for (;;) {
    const ssize_t r = ::read(fds[0], buffer, sizeof buffer);
    if (r < 0 && errno == EINTR) continue;
    if (r <= 0) break;
    text.append(buffer, static_cast<std::size_t>(r));
  }
  ::close(fds[0]);
  std::string error;
  const int status = wait_for_child(pid, error);
  SamplePlan plan;
  plan.pilot_wall_s =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  if (!text.empty() && text[0] == 'E') {
    const std::size_t a = text.find('\n'), b = text.find('\n', a + 1);
    throw InputError(text.substr(1, a - 1), std::stoul(text.substr(a + 1, b - a - 1)),
                     text.substr(b + 1));
  }
  if (status < 0 || !WIFEXITED(status) || WEXITSTATUS(status) != 0 || text.empty() ||
      text[0] != 'J')
    throw std::runtime_error("the --sample-error pilot run failed" +
                             (!text.empty() && text[0] == 'F'
                                  ? ": " + text.substr(1)
                                  : (error.empty() ? std::string() : ": " + error)));
  const auto estimate = nlohmann::ordered_json::parse(text.substr(1));
  plan.every = platform::FrameSample::every_for(estimate, target);
  plan.json["target_error"] = target;
  plan.json["pilot_every"] = pilot.sample_every;
  plan.json["pilot_estimate_s"] = estimate.value("estimate_s", 0.0);
  plan.json["pilot_half_width_relative"] = estimate.value("half_width_relative", 0.0);
  plan.json["pilot_wall_time_s"] = plan.pilot_wall_s;
  plan.json["every"] = plan.every;
  return plan;
}

}  // namespace rtsim::app
