#include "app/image_files.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <fstream>
#include <mutex>
#include <stdexcept>
#include <string>

#include "app/image_io/image_io_api.hpp"
#include "app/module_symbol.hpp"

namespace rtsim::app {
namespace {

constexpr const char* kModule = "librtsim_image_io.so";

/// The module's write function, loaded on first use.
rtsim_write_image_fn load_writer() {
  static std::once_flag once;
  static rtsim_write_image_fn writer = nullptr;
  static std::string tried;
  std::call_once(once, [] {
    writer = reinterpret_cast<rtsim_write_image_fn>(
        find_module_symbol(kModule, kRtsimWriteImageSymbol, false, tried));
  });
  if (!writer)
    throw std::runtime_error(std::string("cannot load rtsim's image module (") + kModule +
                             "; looked for " + tried + ": " +
                             "build it with the rest: cmake --build build)");
  return writer;
}

void write_image(const std::filesystem::path& path, int width, int height, int channels,
                 bool float_data, const void* data, const char* channel_name, bool zip) {
  char error[1024] = {0};
  if (load_writer()(path.c_str(), width, height, channels, float_data ? 1 : 0, data, channel_name,
                    zip ? 1 : 0, error, sizeof error) != 0)
    throw std::runtime_error(error);
}

}  // namespace

void preload_image_module() { (void)load_writer(); }

bool writes_image(const std::vector<std::string>& args) {
  for (std::size_t i = 0; i + 1 < args.size(); ++i)
    if (args[i] == "--image" && args[i + 1] == "none") return false;
  return true;
}

void write_png(const std::filesystem::path& path, int width, int height,
               const std::vector<float>& rgb) {
  std::vector<std::uint8_t> bytes(rgb.size());
  for (std::size_t i = 0; i < rgb.size(); ++i) {
    const float v = std::isfinite(rgb[i]) ? std::clamp(rgb[i], 0.0f, 1.0f) : 0.0f;
    bytes[i] = static_cast<std::uint8_t>(std::lround(v * 255.0f));
  }
  write_image(path, width, height, 3, false, bytes.data(), nullptr, false);
}

void write_exr(const std::filesystem::path& path, int width, int height, int channels,
               const std::vector<float>& data, const char* channel_name) {
  write_image(path, width, height, channels, true, data.data(), channel_name, true);
}

void stage_png(OutputSet& out, const functional::RenderResult& r) {
  write_png(out.stage("image.png"), r.width, r.height, r.rgb);
  if (!r.drawing_svg.empty()) {
    std::ofstream svg(out.stage("drawing.svg"), std::ios::binary);
    svg << r.drawing_svg;
    if (!svg) throw std::runtime_error("cannot write drawing.svg");
  }
}

void stage_images(OutputSet& out, const functional::RenderResult& r) {
  stage_png(out, r);
  write_exr(out.stage("image.exr"), r.width, r.height, 3, r.rgb);
  if (!r.id.empty()) write_exr(out.stage("id.exr"), r.width, r.height, 1, r.id, "id");
  if (!r.depth.empty()) write_exr(out.stage("depth.exr"), r.width, r.height, 1, r.depth, "Z");
}

}  // namespace rtsim::app
