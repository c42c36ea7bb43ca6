#include "firmware/hiddenline/drawing.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>

namespace rtsim::hiddenline {

namespace {

/// Clips the line p0 -> p1 to [0, w] x [0, h] (Liang and Barsky): false if nothing is left.
bool clip(double& x0, double& y0, double& x1, double& y1, double w, double h) {
  double t0 = 0.0, t1 = 1.0;
  const double dx = x1 - x0, dy = y1 - y0;
  const double p[4] = {-dx, dx, -dy, dy};
  const double q[4] = {x0, w - x0, y0, h - y0};
  for (int k = 0; k < 4; ++k) {
    if (p[k] == 0.0) {
      if (q[k] < 0.0) return false;
      continue;
    }
    const double r = q[k] / p[k];
    if (p[k] < 0.0)
      t0 = std::max(t0, r);
    else
      t1 = std::min(t1, r);
    if (t0 > t1) return false;
  }
  const double ax = x0 + t0 * dx, ay = y0 + t0 * dy;
  x1 = x0 + t1 * dx;
  y1 = y0 + t1 * dy;
  x0 = ax;
  y0 = ay;
  return true;
}

}  // namespace

std::vector<std::uint8_t> ink_pixels(const std::vector<VisiblePiece>& pieces,
                                     const ScreenScene& screen, int width, int height) {
  std::vector<std::uint8_t> ink(static_cast<std::size_t>(width) * static_cast<std::size_t>(height),
                                0);
  for (const VisiblePiece& piece : pieces) {
    double x0 = screen.pixel_x(piece.x0), y0 = screen.pixel_y(piece.y0);
    double x1 = screen.pixel_x(piece.x1), y1 = screen.pixel_y(piece.y1);
    if (!std::isfinite(x0) || !std::isfinite(y0) || !std::isfinite(x1) || !std::isfinite(y1))
      continue;
    if (!clip(x0, y0, x1, y1, width, height)) continue;
    const double n = std::ceil(std::max(std::abs(x1 - x0), std::abs(y1 - y0)));
    const auto steps = static_cast<long>(n);
    for (long i = 0; i <= steps; ++i) {
      const double t = steps > 0 ? static_cast<double>(i) / n : 0.0;
      const auto px = static_cast<long>(std::floor(x0 + t * (x1 - x0)));
      const auto py = static_cast<long>(std::floor(y0 + t * (y1 - y0)));
      // The rectangle's far edges (x = w, y = h) belong to the last pixel.
      const long cx = std::clamp(px, 0L, static_cast<long>(width) - 1);
      const long cy = std::clamp(py, 0L, static_cast<long>(height) - 1);
      ink[static_cast<std::size_t>(cy) * static_cast<std::size_t>(width) +
          static_cast<std::size_t>(cx)] = 1;
    }
  }
  return ink;
}

std::string svg_drawing(const std::vector<VisiblePiece>& pieces, const ScreenScene& screen,
                        int width, int height) {
  std::string svg;
  char line[256];
  std::snprintf(line, sizeof line,
                "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"%d\" height=\"%d\" "
                "viewBox=\"0 0 %d %d\">\n<rect width=\"%d\" height=\"%d\" fill=\"white\"/>\n"
                "<g stroke=\"black\" stroke-width=\"1\" stroke-linecap=\"round\">\n",
                width, height, width, height, width, height);
  svg += line;
  for (const VisiblePiece& p : pieces) {
    std::snprintf(line, sizeof line, "<line x1=\"%.3f\" y1=\"%.3f\" x2=\"%.3f\" y2=\"%.3f\"/>\n",
                  screen.pixel_x(p.x0), screen.pixel_y(p.y0), screen.pixel_x(p.x1),
                  screen.pixel_y(p.y1));
    svg += line;
  }
  svg += "</g>\n</svg>\n";
  return svg;
}

}  // namespace rtsim::hiddenline
