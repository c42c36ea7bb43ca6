#include "firmware/accel/grid_divisions.hpp"

#include <algorithm>
#include <cmath>

namespace rtsim::accel {

double UllnerGridModel::time_per_ray_us(int n_s, double n_p) const {
  const double ns = n_s;
  const double n_d = (ns - 1.0) * d_r + 1.0;                  // L614
  const double occupied = (ns - 1.0) * std::sqrt(a_t) + 1.0;  // sqrt(n_o), L642
  const double n_i = ((1.0 - 1.0 / ns) * d_r / (ns * ns) + 1.0 / (occupied * occupied)) * n_p;
  return n_d * t_d_us + n_i * t_i_us + t_l_us;  // L648, L652
}

double UllnerGridModel::density() const {
  return std::cbrt(2.0 * t_i_us * (d_r + 1.0 / a_t) / (d_r * t_d_us));
}

GridDivisions choose_divisions(const Bounds& box, std::size_t primitive_count, double density,
                               std::size_t max_cells) {
  if (primitive_count == 0 || box.empty() || !is_finite(box.lo) || !is_finite(box.hi) ||
      !(density > 0.0)) {
    return {};
  }
  const Vec3 e = box.extent();
  const double largest = max_abs_component(e);
  // Axes thinner than this fraction of the largest extent count as flat (1 division).
  constexpr double kFlatFraction = 1e-9;
  double volume = 1.0;
  int dims = 0;
  for (int a = 0; a < 3; ++a) {
    if (e[a] > kFlatFraction * largest) {
      volume *= e[a];
      ++dims;
    }
  }
  if (dims == 0) return {};
  const double target_cells = std::pow(density, 3.0) * static_cast<double>(primitive_count);
  // Side of a cell: the d-dimensional volume shared among target_cells^(d/3) cells, so that a
  // cube gets k cbrt(N) per axis.
  double side = std::pow(volume, 1.0 / dims) / std::pow(target_cells, 1.0 / 3.0);
  auto divisions_for = [&](double s) {
    int n[3];
    for (int a = 0; a < 3; ++a) {
      n[a] = e[a] > kFlatFraction * largest
                 ? static_cast<int>(std::clamp(std::round(e[a] / s), 1.0, 1e6))
                 : 1;
    }
    return GridDivisions{n[0], n[1], n[2]};
  };
  GridDivisions g = divisions_for(side);
  while (g.cells() > max_cells) {
    side *= 1.05;
    g = divisions_for(side);
  }
  return g;
}

}  // namespace rtsim::accel
