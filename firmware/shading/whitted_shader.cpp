#include "firmware/shading/whitted_shader.hpp"

#include <algorithm>
#include <cmath>

namespace rtsim::shading {
namespace {

double max_component(const Color& c) { return std::max(c.r, std::max(c.g, c.b)); }

/// Offset that lifts a spawned ray off its surface: relative to the coordinates' magnitude (the
/// rounding error of the hit point grows with it) and to the scene extent, and never smaller
/// than the kernel's own position error (approximate kernels such as Wang's subdivision).
double spawn_offset(const Vec3& p, const SurfaceHit& s, const ShadeParams& params) {
  const double rounding = params.offset_relative * (max_abs_component(p) + params.scene_extent);
  return std::max(rounding, 2.0 * s.position_error);
}

}  // namespace

double effective_light_intensity(const ShadeParams& params, std::size_t light_count) {
  if (params.light_intensity > 0.0) return params.light_intensity;
  return light_count == 0 ? 0.0 : 1.0 / std::sqrt(static_cast<double>(light_count));
}

Color miss_contribution(const TracedRay& in, const Color& background) {
  if (in.kind == RayKind::Shadow) return in.light_contribution;
  return in.weight * background;
}

Cost shade_hit(const TracedRay& in, const Hit& hit, const scenes::Material& m,
               std::span<const scenes::Light> lights, const ShadeParams& params, ShadeOutput& out) {
  out.spawned.clear();
  Cost cost;
  const Vec3 d = in.ray.direction;
  const Vec3 p = in.ray.at(hit.surface.t);
  // Two-sided surfaces: face the normals toward the incoming ray.
  Vec3 ng = hit.surface.geometric_normal;
  const bool entering = glm::dot(ng, d) < 0.0;
  if (!entering) ng = -ng;
  Vec3 n = hit.surface.shading_normal;
  if (glm::dot(n, ng) < 0.0) n = -n;
  const Vec3 v = -d;
  const double offset = spawn_offset(p, hit.surface, params);
  const Vec3 p_out = p + offset * ng;  // on the side the ray came from
  cost.fp_mul += 12;
  cost.fp_add += 12;

  // Ambient: R I_a with R = k_d C (seed 000 L414).
  out.local = in.weight * (params.ambient * m.kd) * m.color;

  // One light ray per light (seed 001 §1.7): it carries the light's diffuse and specular terms
  // and adds them if it reaches the light unobstructed. cos i = n.l (seed 000 L444);
  // cos s = (-l + 2 n cos i).v (seed 000 L448, OCR-corrected).
  const double intensity = effective_light_intensity(params, lights.size());
  for (std::size_t k = 0; k < lights.size(); ++k) {
    const Vec3 to_light = lights[k].position - p_out;
    const double dist = glm::length(to_light);
    cost.fp_mul += 6;
    cost.fp_add += 5;
    cost.fp_sqrt += 1;
    if (!(dist > 0.0)) continue;
    const Vec3 l = to_light / dist;
    const double cos_i = glm::dot(n, l);
    if (cos_i <= 0.0 || glm::dot(ng, l) <= 0.0) continue;  // light behind the surface
    Color term = (m.kd * cos_i) * m.color;
    if (m.ks > 0.0 && m.shine > 0.0) {
      const double cos_s = glm::dot(-l + 2.0 * cos_i * n, v);
      if (cos_s > 0.0) term += Color(m.ks * std::pow(cos_s, m.shine));
      cost.fp_mul += 10;
      cost.fp_add += 6;
    }
    const Color contribution = in.weight * intensity * lights[k].color * term;
    if (max_component(contribution) <= 0.0) continue;
    TracedRay s;
    s.ray = Ray{p_out, l};
    s.kind = RayKind::Shadow;
    s.depth = in.depth;
    s.t_max = dist;
    s.weight = Color(0.0);
    s.light_contribution = contribution;
    s.pixel = in.pixel;
    s.light = static_cast<std::uint16_t>(k);
    out.spawned.push_back(s);
  }

  if (in.depth >= params.max_depth) return cost;

  // Reflection weight k_s; refraction weight T. Total internal reflection sends T's share
  // into the reflected ray.
  double reflect_k = m.ks;
  const double cos_in = glm::dot(v, ng);  // > 0
  Vec3 refracted{0.0};
  bool has_refraction = false;
  if (m.transmittance > 0.0) {
    const double eta = entering ? 1.0 / m.ior : m.ior;  // Snell: n1 sin t1 = n2 sin t2
    const double k = 1.0 - eta * eta * (1.0 - cos_in * cos_in);
    cost.fp_mul += 6;
    cost.fp_add += 3;
    if (k < 0.0) {
      reflect_k += m.transmittance;  // total internal reflection
    } else {
      refracted = glm::normalize(eta * d + (eta * cos_in - std::sqrt(k)) * ng);
      has_refraction = true;
      cost.fp_sqrt += 2;
    }
  }
  if (reflect_k > 0.0) {
    const Color w = in.weight * reflect_k;
    if (max_component(w) >= params.contribution_threshold) {
      TracedRay r;
      r.ray = Ray{p_out, glm::normalize(d + 2.0 * cos_in * ng)};
      r.kind = RayKind::Reflected;
      r.depth = static_cast<std::uint8_t>(in.depth + 1);
      r.weight = w;
      r.pixel = in.pixel;
      out.spawned.push_back(r);
      cost.fp_mul += 6;
      cost.fp_add += 3;
    }
  }
  if (has_refraction) {
    const Color w = in.weight * m.transmittance;
    if (max_component(w) >= params.contribution_threshold) {
      TracedRay r;
      r.ray = Ray{p - offset * ng, refracted};  // start on the far side of the surface
      r.kind = RayKind::Refracted;
      r.depth = static_cast<std::uint8_t>(in.depth + 1);
      r.weight = w;
      r.pixel = in.pixel;
      out.spawned.push_back(r);
    }
  }
  return cost;
}

}  // namespace rtsim::shading
