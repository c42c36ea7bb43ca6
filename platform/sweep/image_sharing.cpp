#include "platform/sweep/image_sharing.hpp"

#include <map>
#include <string>
#include <system_error>

#include "params/registry.hpp"
#include "platform/machine.hpp"
#include "platform/machine_registry.hpp"

namespace rtsim::sweep {

namespace fs = std::filesystem;

namespace {

/// What a point's image depends on, as text: equal texts, equal images.
std::string image_key(const Point& p, const params::ParamRegistry& registry) {
  std::string key;
  const auto add = [&key](std::string_view name, std::string_view value) {
    key.append(name).append("=").append(value).append("\n");
  };
  for (std::string_view option : {kMachine, kScene, kWidth, kHeight, std::string_view("image")})
    if (const Setting* s = p.find(option)) add(option, s->value.text);
  for (const auto& s : p.settings)
    if (!is_run_option(s.name) && registry.affects_image(s.name)) add(s.name, s.value.text);
  return key;
}

/// `--image none` in a point's run arguments (replacing the value given, if one was).
void make_timing_only(Point& p) {
  for (std::size_t i = 0; i + 1 < p.args.size(); ++i)
    if (p.args[i] == "--image") {
      p.args[i + 1] = "none";
      return;
    }
  std::size_t at = p.args.size();
  for (std::size_t i = 0; i < p.args.size(); ++i)
    if (p.args[i] == "-q") at = i;
  p.args.insert(p.args.begin() + static_cast<std::ptrdiff_t>(at), {"--image", "none"});
}

}  // namespace

void share_images(const SweepFile& file, std::vector<Point>& points) {
  if (!file.share_images) return;
  std::map<std::string, params::ParamRegistry> registries;  // by machine name
  std::map<std::string, std::size_t> first_of;              // image key -> point index
  for (Point& p : points) {
    if (const Setting* image = p.find("image"); image && image->value.text == "none") continue;
    auto it = registries.find(p.machine());
    if (it == registries.end()) {
      params::ParamRegistry r;
      platform::declare_params_of(&platform::find_machine(p.machine()), r);
      it = registries.emplace(p.machine(), std::move(r)).first;
    }
    const auto [first, inserted] = first_of.emplace(image_key(p, it->second), p.index);
    if (inserted) continue;
    p.image_from = first->second;
    make_timing_only(p);
  }
}

std::size_t fill_shared_images(const std::vector<Point>& points, const fs::path& points_dir,
                               const std::vector<bool>& ok) {
  std::size_t unfilled = 0;
  for (const Point& p : points) {
    if (!p.image_from || !ok[p.index]) continue;
    if (!ok[*p.image_from]) {  // the point that was to render the image failed
      ++unfilled;
      continue;
    }
    const fs::path from = points_dir / points[*p.image_from].key;
    const fs::path to = points_dir / p.key;
    bool filled = false;
    for (const char* name : kImageFiles) {
      std::error_code ec;
      if (!fs::exists(from / name, ec)) continue;
      fs::remove(to / name, ec);
      fs::create_hard_link(from / name, to / name, ec);
      if (ec) {
        ec.clear();
        fs::copy_file(from / name, to / name, fs::copy_options::overwrite_existing, ec);
      }
      if (ec) break;
      filled = true;
    }
    if (!filled) ++unfilled;
  }
  return unfilled;
}

}  // namespace rtsim::sweep
