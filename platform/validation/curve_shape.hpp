#pragma once
// The shape of a sampled curve with one minimum, as Ullner describes Fig. 2-18 (seed 000
// L654-L656): where the minimum is, its value, and whether the curve is steeper on the left.
//
// Steepness compares one halving and one doubling of x around the minimum x*: the rise
// y(x*/2) - y(x*) over the rise y(2 x*) - y(x*), with y interpolated linearly between samples.
// Above 1 means "steeper on the left", Ullner's "less costly to overestimate" (L656).
#include <vector>

namespace rtsim::validation {

struct CurvePoint {
  double x = 0.0;
  double y = 0.0;
};

struct CurveShape {
  double argmin = 0.0;      ///< x of the smallest sample (the first one on ties)
  double minimum = 0.0;     ///< its y
  double left_rise = 0.0;   ///< y(argmin / 2) - minimum
  double right_rise = 0.0;  ///< y(2 argmin) - minimum
  /// left_rise / right_rise; +inf when the right side is flat and the left is not.
  double steepness = 0.0;
  bool left_clamped = false;   ///< argmin / 2 lay before the first sample (first one used)
  bool right_clamped = false;  ///< 2 argmin lay past the last sample (last one used)
};

/// Linear interpolation of the samples at x, clamped to the first and last sample.
/// Points must be sorted by x and not empty.
double interpolate(const std::vector<CurvePoint>& points, double x);

/// Shape of a curve given by samples sorted by increasing x. Throws std::invalid_argument if
/// there are none or they are not sorted.
CurveShape curve_shape(const std::vector<CurvePoint>& points);

}  // namespace rtsim::validation
