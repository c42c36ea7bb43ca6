#include "app/image_files.hpp"

#include <OpenImageIO/imageio.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <stdexcept>

namespace rtsim::app {
namespace {

void write_image(const std::filesystem::path& path, const OIIO::ImageSpec& spec,
                 OIIO::TypeDesc type, const void* data) {
  auto out = OIIO::ImageOutput::create(path.string());
  if (!out) throw std::runtime_error("cannot create " + path.string() + ": " + OIIO::geterror());
  if (!out->open(path.string(), spec) || !out->write_image(type, data) || !out->close())
    throw std::runtime_error("cannot write " + path.string() + ": " + out->geterror());
}

}  // namespace

void write_png(const std::filesystem::path& path, int width, int height,
               const std::vector<float>& rgb) {
  std::vector<std::uint8_t> bytes(rgb.size());
  for (std::size_t i = 0; i < rgb.size(); ++i) {
    const float v = std::isfinite(rgb[i]) ? std::clamp(rgb[i], 0.0f, 1.0f) : 0.0f;
    bytes[i] = static_cast<std::uint8_t>(std::lround(v * 255.0f));
  }
  OIIO::ImageSpec spec(width, height, 3, OIIO::TypeDesc::UINT8);
  write_image(path, spec, OIIO::TypeDesc::UINT8, bytes.data());
}

void write_exr(const std::filesystem::path& path, int width, int height, int channels,
               const std::vector<float>& data, const char* channel_name) {
  OIIO::ImageSpec spec(width, height, channels, OIIO::TypeDesc::FLOAT);
  if (channels == 1) spec.channelnames = {channel_name};
  spec.attribute("compression", "zip");
  // OpenImageIO's EXR writer stamps the current time into DateTime unless one is given; an
  // empty stamp keeps the file a function of the pixels only (same inputs, same bytes).
  spec.attribute("DateTime", "");
  write_image(path, spec, OIIO::TypeDesc::FLOAT, data.data());
}

void stage_images(OutputSet& out, const functional::RenderResult& r) {
  write_png(out.stage("image.png"), r.width, r.height, r.rgb);
  write_exr(out.stage("image.exr"), r.width, r.height, 3, r.rgb);
  if (!r.id.empty()) write_exr(out.stage("id.exr"), r.width, r.height, 1, r.id, "id");
  if (!r.depth.empty()) write_exr(out.stage("depth.exr"), r.width, r.height, 1, r.depth, "Z");
}

}  // namespace rtsim::app
