#include "firmware/sortfirst/screen_regions.hpp"

#include <algorithm>
#include <array>
#include <cmath>

namespace rtsim::sortfirst {

RegionRange classify(const raster::RasterTriangle& t, const raster::ViewTransform& view,
                     const ScreenRegions& regions) {
  RegionRange out;
  if (regions.width <= 0 || regions.height <= 0) return out;
  // The triangle in eye space, clipped to z >= near (Sutherland-Hodgman on one plane): at most
  // four points.
  std::array<Vec3, 3> eye{};
  for (int i = 0; i < 3; ++i) eye[i] = view.to_eye(t.v[static_cast<std::size_t>(i)].position);
  std::array<Vec3, 4> kept{};
  int n = 0;
  for (int i = 0; i < 3; ++i) {
    const Vec3& a = eye[static_cast<std::size_t>(i)];
    const Vec3& b = eye[static_cast<std::size_t>((i + 1) % 3)];
    const bool a_in = a.z >= view.near, b_in = b.z >= view.near;
    if (a_in) kept[static_cast<std::size_t>(n++)] = a;
    if (a_in != b_in) {
      const double s = (view.near - a.z) / (b.z - a.z);
      Vec3 p = a + (b - a) * s;
      p.z = view.near;
      kept[static_cast<std::size_t>(n++)] = p;
    }
  }
  if (n == 0) return out;
  double x_lo = INFINITY, x_hi = -INFINITY, y_lo = INFINITY, y_hi = -INFINITY;
  for (int i = 0; i < n; ++i) {
    const Vec3& p = kept[static_cast<std::size_t>(i)];
    const double sx = view.screen_x(p), sy = view.screen_y(p);
    x_lo = std::min(x_lo, sx);
    x_hi = std::max(x_hi, sx);
    y_lo = std::min(y_lo, sy);
    y_hi = std::max(y_hi, sy);
  }
  // Pixels whose column or row the box reaches; a box that reaches no pixel is off the screen.
  if (!(x_hi >= 0.0 && y_hi >= 0.0 && x_lo < regions.width && y_lo < regions.height)) return out;
  const auto clamp_pixel = [](double v, int size) {
    return static_cast<int>(std::clamp(std::floor(v), 0.0, static_cast<double>(size - 1)));
  };
  out.on_screen = true;
  out.c0 = regions.col_of(clamp_pixel(x_lo, regions.width));
  out.c1 = regions.col_of(clamp_pixel(x_hi, regions.width));
  out.r0 = regions.row_of(clamp_pixel(y_lo, regions.height));
  out.r1 = regions.row_of(clamp_pixel(y_hi, regions.height));
  return out;
}

}  // namespace rtsim::sortfirst
