#include "platform/validation/curve_shape.hpp"

#include <limits>
#include <stdexcept>

namespace rtsim::validation {

double interpolate(const std::vector<CurvePoint>& points, double x) {
  if (points.empty()) throw std::invalid_argument("interpolate: no samples");
  if (x <= points.front().x) return points.front().y;
  if (x >= points.back().x) return points.back().y;
  for (std::size_t i = 1; i < points.size(); ++i) {
    const CurvePoint& a = points[i - 1];
    const CurvePoint& b = points[i];
    if (x <= b.x) {
      const double f = (x - a.x) / (b.x - a.x);
      return a.y + f * (b.y - a.y);
    }
  }
  return points.back().y;
}

CurveShape curve_shape(const std::vector<CurvePoint>& points) {
  if (points.empty()) throw std::invalid_argument("curve_shape: no samples");
  for (std::size_t i = 1; i < points.size(); ++i) {
    if (!(points[i].x > points[i - 1].x))
      throw std::invalid_argument("curve_shape: samples not sorted by increasing x");
  }
  CurveShape s;
  s.argmin = points.front().x;
  s.minimum = points.front().y;
  for (const CurvePoint& p : points) {
    if (p.y < s.minimum) {
      s.minimum = p.y;
      s.argmin = p.x;
    }
  }
  const double left_x = s.argmin / 2.0;
  const double right_x = s.argmin * 2.0;
  s.left_clamped = left_x < points.front().x;
  s.right_clamped = right_x > points.back().x;
  s.left_rise = interpolate(points, left_x) - s.minimum;
  s.right_rise = interpolate(points, right_x) - s.minimum;
  if (s.right_rise > 0.0) {
    s.steepness = s.left_rise / s.right_rise;
  } else {
    s.steepness = s.left_rise > 0.0 ? std::numeric_limits<double>::infinity() : 0.0;
  }
  return s;
}

}  // namespace rtsim::validation
