// The camera path's parameters, each named once.
#include "platform/machines/pxpl5_raytrace/camera_path.hpp"

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
     .source = "assumption: a camera path for frame rates (the issue's multi-frame runs)"});
const modules::RealParam kSpin({.name = "camera.spin",
                                .default_value = "0",
                                .min = "-360",
                                .max = "360",
                                .unit = "degrees",
                                .description = "Turn of the eye about the vertical axis (the "
                                               "view's up through the point looked at) from one "
                                               "frame to the next",
                                .source = "assumption: a simple camera path"});
const modules::RealParam kDistance(
    {.name = "camera.distance",
     .default_value = "1",
     .min = "0.01",
     .max = "100",
     .unit = "x",
     .description = "The eye's distance from the point it looks at, times the scene's (larger: "
                    "the scene covers less of the screen)",
     .source = "seed 004 L369: Fig. 9 varies screen coverage by viewing distance"});

}  // namespace

void CameraPath::declare_params(params::ParamRegistry& r) {
  const modules::ParamDecls top(r, "", false);
  top.add(kFrames);
  top.add(kSpin);
  top.add(kDistance);
}

CameraPath CameraPath::read(const params::ParamRegistry& r) {
  const modules::ModuleParams p(r, "");
  return {.frames = static_cast<int>(p.get(kFrames)),
          .spin_deg = p.get(kSpin),
          .distance = p.get(kDistance)};
}

}  // namespace rtsim::platform::pxpl5
