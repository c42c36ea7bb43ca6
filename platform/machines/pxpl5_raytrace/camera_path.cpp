// The camera path's parameters, each named once.
#include "platform/machines/pxpl5_raytrace/camera_path.hpp"

#include <algorithm>
#include <sstream>
#include <string>

#include "common/input_error.hpp"
#include "common/suggest.hpp"
#include "modules/module_params.hpp"

namespace rtsim::platform::pxpl5 {

namespace {

const modules::CountParam kFrames(
    {.name = "frames",
     .default_value = "1",
     .min = "1",
     .max = "100000",
     .unit = "frames",
     .description = "Frames rendered; the camera turns between them (camera.spin) and the image "
                    "is the last frame's",
     .source = "study setting: a camera path for frame rates (the issue's multi-frame runs)",
     .affects_image = true});
const modules::ChoiceParam kPath(
    {.name = "camera.path",
     .default_value = "",
     .description =
         "The user's session, as segments of frames: \"move N\" (the user moves during each of "
         "N frames: the next frame's view is turned camera.spin degrees) and \"rest N\" (the "
         "view stays), comma-separated, e.g. \"move 4, rest 6\". Sets the frame count. Empty: "
         "`frames` frames, all moving unless camera.spin is 0",
     .source = "seed 004 L288 (a coarse image while the view changes, refinement during "
               "pauses); assumption: a turn about the vertical axis stands for the user's "
               "motion",
     .affects_image = true});
const modules::RealParam kSpin({.name = "camera.spin",
                                .default_value = "0",
                                .min = "-360",
                                .max = "360",
                                .unit = "degrees",
                                .description = "Turn of the eye about the vertical axis (the "
                                               "view's up through the point looked at) after "
                                               "each frame during which the user moves",
                                .source = "study setting: a simple camera path",
                                .affects_image = true});
const modules::RealParam kDistance(
    {.name = "camera.distance",
     .default_value = "1",
     .min = "0.01",
     .max = "100",
     .unit = "x",
     .description = "The eye's distance from the point it looks at, times the scene's (larger: "
                    "the scene covers less of the screen)",
     .source = "seed 004 L369: Fig. 9 varies screen coverage by viewing distance",
     .affects_image = true});

}  // namespace

void CameraPath::declare_params(params::ParamRegistry& r) {
  const modules::ParamDecls top(r, "", false);
  top.add(kFrames);
  top.add(kPath);
  top.add(kSpin);
  top.add(kDistance);
}

namespace {

[[noreturn]] void bad_path(const modules::ModuleParams& p, const std::string& what) {
  throw InputError(kPath.name() + " (set at " + p.where_set(kPath.name()) + ")", 0,
                   "pxpl5-raytrace: " + what);
}

/// "move 4, rest 6" as each frame's moving flag.
std::vector<bool> parse_path(const modules::ModuleParams& p, const std::string& text) {
  std::vector<bool> moving;
  std::size_t at = 0;
  while (at <= text.size()) {
    const std::size_t comma = std::min(text.find(',', at), text.size());
    std::istringstream segment(text.substr(at, comma - at));
    std::string kind, extra;
    long n = 0;
    segment >> kind;
    if (kind.empty())
      bad_path(p, "an empty segment in \"" + text + "\" (expected \"move N\" or \"rest N\")");
    if (kind != "move" && kind != "rest") {
      bad_path(p, "unknown segment \"" + kind + "\" (expected \"move N\" or \"rest N\")" +
                      did_you_mean(kind, {"move", "rest"}));
    }
    if (!(segment >> n) || (segment >> extra) || n < 1 || n > 100000)
      bad_path(p, "\"" + kind + "\" takes a frame count from 1 to 100000 (\"" + kind + " 4\")");
    moving.insert(moving.end(), static_cast<std::size_t>(n), kind == "move");
    if (moving.size() > 100000) bad_path(p, "more than 100000 frames");
    at = comma + 1;
  }
  return moving;
}

}  // namespace

CameraPath CameraPath::read(const params::ParamRegistry& r) {
  const modules::ModuleParams p(r, "");
  CameraPath path{.frames = static_cast<int>(p.get(kFrames)),
                  .spin_deg = p.get(kSpin),
                  .distance = p.get(kDistance),
                  .moving = {},
                  .turns_left = {}};
  const std::string text = p.get(kPath);
  if (text.find_first_not_of(" \t") == std::string::npos) {
    path.moving.assign(static_cast<std::size_t>(path.frames), path.spin_deg != 0.0);
  } else {
    path.moving = parse_path(p, text);
    const int n = static_cast<int>(path.moving.size());
    if (p.where_set(kFrames.name()) != "default" && path.frames != n)
      bad_path(p, "the path has " + std::to_string(n) +
                      " frames but frames = " + std::to_string(path.frames) + " (set at " +
                      p.where_set(kFrames.name()) + "): leave frames unset with a path");
    path.frames = n;
  }
  // Counted once from the last frame back (a frame's camera is turned back from the last's).
  path.turns_left.assign(static_cast<std::size_t>(path.frames), 0);
  for (int f = path.frames - 2; f >= 0; --f)
    path.turns_left[static_cast<std::size_t>(f)] =
        path.turns_left[static_cast<std::size_t>(f) + 1] +
        (path.moving[static_cast<std::size_t>(f)] ? 1 : 0);
  return path;
}

}  // namespace rtsim::platform::pxpl5
