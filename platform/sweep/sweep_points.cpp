#include "platform/sweep/sweep_points.hpp"

#include <cstdint>
#include <cstdio>
#include <stdexcept>

#include "platform/runs/run_request.hpp"
#include "scenes/scene_loader.hpp"

namespace rtsim::sweep {

namespace fs = std::filesystem;

const Setting* Point::find(std::string_view name) const {
  for (const auto& s : settings)
    if (s.name == name) return &s;
  return nullptr;
}

const std::string& Point::machine() const {
  const Setting* s = find(kMachine);
  if (!s) throw std::logic_error("sweep point without a machine");
  return s->value.text;
}

const std::string& Point::scene() const {
  const Setting* s = find(kScene);
  if (!s) throw std::logic_error("sweep point without a scene");
  return s->value.text;
}

std::string Point::swept_text(std::string_view separator) const {
  std::string s;
  for (const auto& setting : settings) {
    if (!setting.swept) continue;
    if (!s.empty()) s += separator;
    s += setting.name + "=" + setting.value.text;
  }
  return s;
}

std::string Point::command_line() const {
  runs::RunRequest r;
  r.args = args;
  return r.command_line();
}

std::string Point::hash() const { return fnv1a64_hex(command_line()); }

std::string fnv1a64_hex(std::string_view text) {
  std::uint64_t h = 0xcbf29ce484222325ULL;  // FNV-1a offset basis
  for (unsigned char c : text) {
    h ^= c;
    h *= 0x100000001b3ULL;  // FNV prime
  }
  char buf[17];
  std::snprintf(buf, sizeof buf, "%016llx", static_cast<unsigned long long>(h));
  return buf;
}

std::string scene_argument(const SweepFile& file, const std::string& scene) {
  if (scene.starts_with(scenes::kBuiltinPrefix)) return scene;
  fs::path p = scene;
  if (p.is_relative()) p = file.base_dir / p;
  return p.lexically_normal().string();
}

std::vector<Point> expand_points(const SweepFile& file) {
  const std::size_t n = file.point_count();
  // At least four digits, more when the sweep needs them, so folders sort in point order.
  std::size_t digits = 4;
  for (std::size_t limit = 10000; n > limit; limit *= 10) ++digits;

  std::vector<Point> points;
  points.reserve(n);
  for (std::size_t index = 0; index < n; ++index) {
    Point p;
    p.index = index;
    p.key = std::to_string(index);
    if (p.key.size() < digits) p.key.insert(0, digits - p.key.size(), '0');
    for (const auto& f : file.fixed) p.settings.push_back({f.name, f.value, false, f.value.line});
    // Mixed-radix digits of the index, the last axis fastest.
    std::vector<std::size_t> at(file.axes.size());
    std::size_t rest = index;
    for (std::size_t a = file.axes.size(); a-- > 0;) {
      at[a] = rest % file.axes[a].size();
      rest /= file.axes[a].size();
    }
    for (std::size_t a = 0; a < file.axes.size(); ++a)
      for (const auto& m : file.axes[a].members)
        p.settings.push_back({m.name, m.values[at[a]], true, m.line});

    p.args = {"run", "--machine", p.machine(), "--scene", scene_argument(file, p.scene())};
    for (std::string_view option : {kWidth, kHeight})
      if (const Setting* s = p.find(option)) {
        p.args.push_back("--" + std::string(option));
        p.args.push_back(s->value.text);
      }
    // The run flags: as `rtsim run` takes them; "off" values add nothing.
    bool traced = false, capped = false, sampled = false;
    for (const auto& s : p.settings)
      sampled = sampled || (s.name == "sample" && s.value.text != "0") ||
                (s.name == "sample-error" && s.value.text != "none");
    for (const auto& s : p.settings) {
      if (!is_run_flag(s.name)) continue;
      const std::string& v = s.value.text;
      // The window, warm-up and work count of a sampled run: nothing at a point in full detail
      // (an axis `sample = [0, 8]` holds the reference).
      if (!sampled && (s.name == "sample-window" || s.name == "sample-warmup" ||
                       s.name == "sample-work-stride"))
        continue;
      if (s.name == "latency-probe") {
        if (s.value.json == true) p.args.push_back("--latency-probe");
        continue;
      }
      if ((s.name == "sample" && v == "0") || (s.name == "sample-error" && v == "none") ||
          (s.name == "trace" && v == "none"))
        continue;
      traced = traced || s.name == "trace";
      capped = capped || s.name == "trace-max-events";
      p.args.push_back("--" + s.name);
      p.args.push_back(v);
    }
    if (traced && !capped) {
      p.args.push_back("--trace-max-events");
      p.args.push_back(std::to_string(kSweepTraceMaxEvents));
    }
    p.args.push_back("-q");
    for (const auto& [config, line] : file.configs) {
      p.args.push_back("--config");
      p.args.push_back(config.string());
    }
    for (const auto& s : p.settings) {
      if (is_run_option(s.name)) continue;
      p.args.push_back("-p");
      p.args.push_back(s.name + "=" + s.value.text);
    }
    points.push_back(std::move(p));
  }
  return points;
}

}  // namespace rtsim::sweep
