#pragma once
// The interface between rtsim and its image-file module (librtsim_image_io.so, built from
// app/image_io/oiio_module.cpp). OpenImageIO brings some 250 shared libraries (OpenCV, ffmpeg,
// GDAL, ...) whose loading took 0.6 s of every rtsim start; in a module, only a command that
// writes an image loads them, when it first does (app/image_files.cpp), and `rtsim sweep` and
// `rtsim validate` load them once before forking their runs.
//
// Plain C types only: the module and the program need not agree on any C++ class layout.
#include <cstddef>

extern "C" {

/// Writes a `width` x `height` image of `channels` channels, 8-bit (`float_data` 0) or 32-bit
/// float, to `path` (the format from its extension). `channel_name` names a single channel;
/// `zip` asks for ZIP compression (EXR); an EXR gets an empty DateTime so that the file is a
/// function of the pixels only. Returns 0, or -1 with a message in `error` (`error_size` bytes).
typedef int (*rtsim_write_image_fn)(const char* path, int width, int height, int channels,
                                    int float_data, const void* data, const char* channel_name,
                                    int zip, char* error, std::size_t error_size);

/// The module's one entry point, looked up by this name.
inline constexpr const char* kRtsimWriteImageSymbol = "rtsim_write_image";
}
