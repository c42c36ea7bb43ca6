// librtsim_image_io.so: rtsim's image writing through OpenImageIO, loaded on first use
// (app/image_io/image_io_api.hpp says why).
#include <OpenImageIO/imageio.h>

#include <cstring>
#include <string>

#include "app/image_io/image_io_api.hpp"

namespace {

int fail(const std::string& message, char* error, std::size_t error_size) {
  if (error && error_size > 0) {
    std::strncpy(error, message.c_str(), error_size - 1);
    error[error_size - 1] = '\0';
  }
  return -1;
}

}  // namespace

extern "C" __attribute__((visibility("default"))) int rtsim_write_image(
    const char* path, int width, int height, int channels, int float_data, const void* data,
    const char* channel_name, int zip, char* error, std::size_t error_size) {
  const OIIO::TypeDesc type = float_data ? OIIO::TypeDesc::FLOAT : OIIO::TypeDesc::UINT8;
  OIIO::ImageSpec spec(width, height, channels, type);
  if (channels == 1 && channel_name) spec.channelnames = {channel_name};
  if (zip) spec.attribute("compression", "zip");
  // OpenImageIO's EXR writer stamps the current time into DateTime unless one is given.
  if (float_data) spec.attribute("DateTime", "");
  auto out = OIIO::ImageOutput::create(path);
  if (!out)
    return fail(std::string("cannot create ") + path + ": " + OIIO::geterror(), error, error_size);
  if (!out->open(path, spec) || !out->write_image(type, data) || !out->close())
    return fail(std::string("cannot write ") + path + ": " + out->geterror(), error, error_size);
  return 0;
}
