#pragma once
// A sweep renders each distinct image once. Its points differ in what the axes vary; the image
// depends only on the machine, the scene, the size and the parameters marked as affecting it
// (params::ParamSpec::affects_image: what the machine's functional twin reads; every other
// parameter leaves the image byte-identical, tests/image_params_test.cpp). Of the points that
// agree on all of those, the first (in point order) renders the image; the others run
// timing-only (`rtsim run --image none`: with --sample, the rows not simulated in detail are not
// rendered at all) and, once the points have run, get the first's image files in their folders.
// A sweep file's `share-images = false` turns this off (docs/sweeps.md).
#include <cstddef>
#include <filesystem>
#include <vector>

#include "platform/sweep/sweep_file.hpp"
#include "platform/sweep/sweep_points.hpp"

namespace rtsim::sweep {

/// The image files a point's folder may hold (`rtsim run --image`, --aov).
inline constexpr const char* kImageFiles[] = {"image.png", "image.exr", "id.exr", "depth.exr"};

/// Sets Point::image_from of every point whose image an earlier point renders, and makes it
/// timing-only (its args then say `--image none`). Call after check_sweep: every name is known.
void share_images(const SweepFile& file, std::vector<Point>& points);

/// After the points ran: each point with image_from whose run succeeded (`ok`, by point index)
/// gets its image point's files (hard links where the file system allows, else copies). Returns
/// how many of those folders could not be filled (the image point failed, a file system without
/// room, a rank's folder on another node), 0 when all were.
std::size_t fill_shared_images(const std::vector<Point>& points,
                               const std::filesystem::path& points_dir,
                               const std::vector<bool>& ok);

}  // namespace rtsim::sweep
