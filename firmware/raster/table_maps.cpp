#include "firmware/raster/table_maps.hpp"

#include <algorithm>
#include <cmath>

namespace rtsim::raster {

MipMap::MipMap(int size, std::vector<std::uint8_t> rgb) : size_(size) {
  levels_.push_back(std::move(rgb));
  for (int s = size; s > 1; s /= 2) {
    const auto& hi = levels_.back();
    const int h = s / 2;
    std::vector<std::uint8_t> lo(static_cast<std::size_t>(3 * h * h));
    for (int y = 0; y < h; ++y)
      for (int x = 0; x < h; ++x)
        for (int c = 0; c < 3; ++c) {
          const auto at = [&](int xx, int yy) {
            return static_cast<int>(hi[static_cast<std::size_t>(3 * (yy * s + xx) + c)]);
          };
          const int sum = at(2 * x, 2 * y) + at(2 * x + 1, 2 * y) + at(2 * x, 2 * y + 1) +
                          at(2 * x + 1, 2 * y + 1);
          lo[static_cast<std::size_t>(3 * (y * h + x) + c)] =
              static_cast<std::uint8_t>((sum + 2) / 4);
        }
    levels_.push_back(std::move(lo));
  }
}

std::size_t MipMap::bytes() const {
  std::size_t b = 0;
  for (const auto& l : levels_) b += l.size();
  return b;
}

Color MipMap::texel(int level, int x, int y) const {
  const int s = std::max(1, size_ >> level);
  x = ((x % s) + s) % s;
  y = ((y % s) + s) % s;
  const auto& l = levels_[static_cast<std::size_t>(level)];
  const std::size_t i = static_cast<std::size_t>(3 * (y * s + x));
  return Color(l[i], l[i + 1], l[i + 2]) / 255.0;
}

Color MipMap::lookup(double u, double v, double fu, double fv) const {
  if (levels_.empty()) return Color(1.0);
  // The level whose texel is as large as the footprint (nearest level, bilinear inside it).
  const double footprint = std::max(fu, fv) * size_;
  const int top = static_cast<int>(levels_.size()) - 1;
  const int level =
      footprint > 1.0 ? std::clamp(static_cast<int>(std::lround(std::log2(footprint))), 0, top) : 0;
  const int s = std::max(1, size_ >> level);
  const double x = (u - std::floor(u)) * s - 0.5, y = (v - std::floor(v)) * s - 0.5;
  const int x0 = static_cast<int>(std::floor(x)), y0 = static_cast<int>(std::floor(y));
  const double ax = x - x0, ay = y - y0;
  return (1.0 - ay) * ((1.0 - ax) * texel(level, x0, y0) + ax * texel(level, x0 + 1, y0)) +
         ay * ((1.0 - ax) * texel(level, x0, y0 + 1) + ax * texel(level, x0 + 1, y0 + 1));
}

void DepthMap::store(const RegionDepths& region) {
  const auto& g = region.at;
  for (int y = 0; y < g.height; ++y)
    for (int x = 0; x < g.width; ++x)
      depth_[static_cast<std::size_t>(g.y0 + y) * static_cast<std::size_t>(view_.width) +
             static_cast<std::size_t>(g.x0 + x)] =
          region.depth[static_cast<std::size_t>(y * kRegionWidth + x)];
}

bool DepthMap::lit(const Vec3& p, const Vec3& n, double bias_texels) const {
  const Vec3 e = view_.to_eye(p);
  if (!(e.z > view_.near)) return true;
  const double sx = view_.screen_x(e), sy = view_.screen_y(e);
  if (!(sx >= 0.0 && sy >= 0.0 && sx < view_.width && sy < view_.height)) return true;
  const std::uint32_t word = at(static_cast<int>(sx), static_cast<int>(sy));
  if (word == kBackgroundDepth) return true;
  // The bias grows with the surface's slope to the light (tan of the angle, at most 8).
  const Vec3 to_light = glm::normalize(view_.origin - p);
  const double c = std::clamp(std::fabs(glm::dot(n, to_light)), 0.125, 1.0);
  const double slope = std::sqrt(1.0 - c * c) / c;
  const double texel = e.z * view_.pixel;
  return e.z - bias_texels * texel * (1.0 + slope) <= view_.depth_of(word);
}

void ColourMap::set(int x, int y, const Color& c) {
  const std::size_t i = 3 * (static_cast<std::size_t>(y) * static_cast<std::size_t>(view_.width) +
                             static_cast<std::size_t>(x));
  rgb_[i] = colour_byte(c.r);
  rgb_[i + 1] = colour_byte(c.g);
  rgb_[i + 2] = colour_byte(c.b);
}

Color ColourMap::lookup(const Vec3& p) const {
  const Vec3 e = view_.to_eye(p);
  double sx = e.z > view_.near ? view_.screen_x(e) : 0.0;
  double sy = e.z > view_.near ? view_.screen_y(e) : 0.0;
  if (!std::isfinite(sx) || !std::isfinite(sy)) sx = sy = 0.0;
  // Clamped in floating point first: a point far outside the map reads its nearest edge.
  const int x = static_cast<int>(std::clamp(std::floor(sx), 0.0, double(view_.width - 1)));
  const int y = static_cast<int>(std::clamp(std::floor(sy), 0.0, double(view_.height - 1)));
  const std::size_t i = 3 * (static_cast<std::size_t>(y) * static_cast<std::size_t>(view_.width) +
                             static_cast<std::size_t>(x));
  return Color(rgb_[i], rgb_[i + 1], rgb_[i + 2]) / 255.0;
}

}  // namespace rtsim::raster
