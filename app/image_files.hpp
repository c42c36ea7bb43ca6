#pragma once
// Image outputs through OpenImageIO: image.png (8-bit), image.exr and the AOVs (32-bit float).
// OpenImageIO lives in a module loaded when the first image is written
// (app/image_io/image_io_api.hpp).
#include <filesystem>
#include <vector>

#include "app/output_set.hpp"
#include "platform/functional/functional_renderer.hpp"

namespace rtsim::app {

/// Loads the image module now (`rtsim sweep` and `rtsim validate`, before they fork their runs,
/// so that no run loads it again). Throws std::runtime_error if it cannot be loaded.
void preload_image_module();

/// Whether an `rtsim run` command line writes an image (it has no `--image none`): whether a
/// parent that forks it should preload the image module for it.
bool writes_image(const std::vector<std::string>& args);

/// Linear RGB floats to an 8-bit PNG: each channel clamped to [0,1] and rounded (no transfer
/// curve: the machines' frame buffers held linear intensities).
void write_png(const std::filesystem::path& path, int width, int height,
               const std::vector<float>& rgb);

/// Float EXR with `channels` channels (3: R,G,B; 1: named `channel_name`).
void write_exr(const std::filesystem::path& path, int width, int height, int channels,
               const std::vector<float>& data, const char* channel_name = "Y");

/// Stages image.png, image.exr and the AOVs the result carries (id.exr, depth.exr) in `out`, and
/// drawing.svg when the result has a line drawing (RenderResult::drawing_svg).
void stage_images(OutputSet& out, const functional::RenderResult& r);
/// Stages image.png only (rtsim run --image png), and drawing.svg as above.
void stage_png(OutputSet& out, const functional::RenderResult& r);

}  // namespace rtsim::app
