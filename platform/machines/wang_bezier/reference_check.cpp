#include "platform/machines/wang_bezier/reference_check.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "firmware/kernels/bezier_reference.hpp"

namespace rtsim::platform::wang_bezier {

namespace {
/// Nearest-rank quantile of `v` (reordered), 0 if empty.
double quantile(std::vector<double>& v, double q) {
  if (v.empty()) return 0.0;
  const auto k = static_cast<std::size_t>(std::ceil(q * static_cast<double>(v.size()))) - (q > 0);
  const auto nth = v.begin() + static_cast<std::ptrdiff_t>(std::min(k, v.size() - 1));
  std::nth_element(v.begin(), nth, v.end());
  return *nth;
}

nlohmann::ordered_json distribution(std::vector<double> v) {
  double sum = 0;
  for (double e : v) sum += e;
  return {{"mean", v.empty() ? 0.0 : sum / static_cast<double>(v.size())},
          {"p10", quantile(v, 0.10)},
          {"p50", quantile(v, 0.50)},
          {"p90", quantile(v, 0.90)},
          {"p99", quantile(v, 0.99)},
          {"max", quantile(v, 1.0)}};
}

struct Found {
  bool hit = false;
  double t = 0;
  Vec3 point{0.0};
  double size = 1;  ///< the patch's control-box diagonal
};
}  // namespace

void Agreement::add(bool pipeline_hit, bool reference_hit, double point, double depth, double width,
                    double footprint) {
  ++compared;
  if (pipeline_hit && reference_hit) {
    ++both;
    if (point > kAnotherSurfaceWidths * width) {
      ++another_surface;
      return;
    }
    point_error.push_back(point);
    depth_error.push_back(depth);
    if (footprint > 0) pixel_error.push_back(point / footprint);
  } else if (pipeline_hit) {
    ++phantom;
  } else if (reference_hit) {
    ++missed;
  } else {
    ++neither;
  }
}

nlohmann::ordered_json Agreement::to_json() const {
  const auto n = static_cast<double>(compared);
  const auto hits = static_cast<double>(both + missed);
  const auto wrong = static_cast<double>(missed + phantom);
  nlohmann::ordered_json j = {
      {"compared", compared},
      {"both", both},
      {"neither", neither},
      {"missed", missed},
      {"phantom", phantom},
      {"another_surface", another_surface},
      {"disagreement", n > 0 ? wrong / n : 0.0},
      {"disagreement_of_hits", hits > 0 ? wrong / hits : 0.0},
      {"wrong_of_hits", hits > 0 ? (wrong + static_cast<double>(another_surface)) / hits : 0.0},
      {"point_error", distribution(point_error)},
      {"depth_error", distribution(depth_error)}};
  if (!pixel_error.empty()) j["pixel_error"] = distribution(pixel_error);
  return j;
}

void ReferenceCheck::ray(const Ray& ray, double t_min, double t_max, bool primary,
                         const std::map<std::uint32_t, kernels::WangResult<double>>& answers) {
  if (answers.empty()) return;
  const double t_enter = kernels::BezierPatchKernel::entry_t(t_min);
  const double no_footprint = std::numeric_limits<double>::quiet_NaN();
  Found near_pipeline, near_reference;
  for (const auto& [slot, answer] : answers) {
    const auto& kernel = *std::get<functional::PatchShape>(geometry_.shapes[slot].shape).kernel;
    const double size = glm::length(kernel.bounds().extent());
    Found p, r;
    SurfaceHit s;
    if (kernel.finish(answer, ray, t_min, t_max, s)) p = {true, s.t, Vec3(answer.point), size};
    if (kernels::reference_intersect(kernel.original(), ray, t_enter, t_max, s))
      r = {true, s.t, ray.at(s.t), size};
    jobs_.add(p.hit, r.hit, glm::length(p.point - r.point) / size, std::fabs(p.t - r.t) / size,
              width_, no_footprint);
    if (p.hit && (!near_pipeline.hit || p.t < near_pipeline.t)) near_pipeline = p;
    if (r.hit && (!near_reference.hit || r.t < near_reference.t)) near_reference = r;
  }
  if (!primary) return;
  const Found& unit = near_reference.hit ? near_reference : near_pipeline;
  // A pixel's width where the reference hit, in the patch's sizes (ray directions are unit).
  const double footprint = pixel_angle_ * near_reference.t / unit.size;
  rays_.add(near_pipeline.hit, near_reference.hit,
            glm::length(near_pipeline.point - near_reference.point) / unit.size,
            std::fabs(near_pipeline.t - near_reference.t) / unit.size, width_, footprint);
}

nlohmann::ordered_json ReferenceCheck::to_json() const {
  return {{"jobs", jobs_.to_json()}, {"rays", rays_.to_json()}};
}

}  // namespace rtsim::platform::wang_bezier
