#include "firmware/geometry/convex_quads.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <unordered_map>

#include "firmware/geometry/triangulate.hpp"
#include "firmware/kernels/ullner_quad.hpp"

namespace rtsim::geometry {

std::string_view to_string(PolygonRepair r) {
  switch (r) {
    case PolygonRepair::DuplicateVertex:
      return "duplicate vertex";
    case PolygonRepair::CollinearVertex:
      return "collinear vertex";
    case PolygonRepair::NonPlanar:
      return "non-planar (triangles only)";
    case PolygonRepair::NormalsDropped:
      return "normals dropped";
    case PolygonRepair::kCount:
      break;
  }
  return "unknown";
}

std::string_view to_string(PolygonRejection r) {
  switch (r) {
    case PolygonRejection::TooFewVertices:
      return "too few vertices";
    case PolygonRejection::NonFiniteVertex:
      return "non-finite vertex";
    case PolygonRejection::ZeroArea:
      return "zero area";
    case PolygonRejection::NotSimple:
      return "self-intersecting";
    case PolygonRejection::kCount:
      break;
  }
  return "unknown";
}

void ConvexQuadReport::merge(const ConvexQuadReport& o) {
  polygons += o.polygons;
  converted += o.converted;
  repaired += o.repaired;
  rejected += o.rejected;
  quads += o.quads;
  triangles += o.triangles;
  triangles_dropped += o.triangles_dropped;
  for (std::size_t i = 0; i < repairs.size(); ++i) repairs[i] += o.repairs[i];
  for (std::size_t i = 0; i < rejections.size(); ++i) rejections[i] += o.rejections[i];
}

std::string ConvexQuadReport::summary() const {
  auto list = [](const auto& counts, auto name_of) {
    std::string s;
    for (std::size_t i = 0; i < counts.size(); ++i) {
      if (counts[i] == 0) continue;
      if (!s.empty()) s += ", ";
      s += std::to_string(counts[i]) + " " + std::string(name_of(static_cast<std::uint8_t>(i)));
    }
    return s;
  };
  std::string s =
      std::to_string(polygons) + " polygons: " + std::to_string(converted) + " converted";
  if (repaired > 0) {
    s += " (" + std::to_string(repaired) + " repaired: " +
         list(repairs, [](std::uint8_t i) { return to_string(static_cast<PolygonRepair>(i)); }) +
         ")";
  }
  s += ", " + std::to_string(rejected) + " rejected";
  if (rejected > 0) {
    s += " (" +
         list(rejections,
              [](std::uint8_t i) { return to_string(static_cast<PolygonRejection>(i)); }) +
         ")";
  }
  s += "; " + std::to_string(quads) + " quads, " + std::to_string(triangles) + " triangles";
  if (triangles_dropped > 0) {
    s += ", " + std::to_string(triangles_dropped) + " degenerate triangles dropped";
  }
  return s;
}

namespace {

using Tri = std::array<std::uint32_t, 3>;

/// Smallest turning sine of the corners of a (counter-clockwise about n) polygon; negative when
/// a corner turns the wrong way.
double min_corner_sine(const std::array<Vec3, 4>& q, const Vec3& n) {
  double m = kInfinity;
  for (std::size_t i = 0; i < 4; ++i) {
    const Vec3 e1 = q[i] - q[(i + 3) % 4];
    const Vec3 e2 = q[(i + 1) % 4] - q[i];
    const double l = glm::length(e1) * glm::length(e2);
    if (!(l > 0.0)) return -1.0;
    m = std::min(m, glm::dot(glm::cross(e1, e2), n) / l);
  }
  return m;
}

/// A proper (non-triangle) quad that the Ullner host accepts, with no nearly straight corner.
bool acceptable_quad(const std::array<Vec3, 4>& q) {
  const auto pre = kernels::UllnerQuadParams<double>::precompute_checked(q[0], q[1], q[2], q[3]);
  if (!pre.ok()) return false;
  if (pre.params->u_family == kernels::QuadFamily::Pencil ||
      pre.params->u_family == kernels::QuadFamily::Deflated) {
    return false;  // a collapsed edge: that is a triangle
  }
  return min_corner_sine(q, pre.params->n_p()) >= kMinQuadCornerSine;
}

ConvexQuad make_triangle(const Vec3& a, const Vec3& b, const Vec3& c, const Vec3* na,
                         const Vec3* nb, const Vec3* nc) {
  ConvexQuad q;
  q.corners = {a, b, c, c};  // p00, p10, p11 = p01: the v = 1 edge collapsed
  q.triangle = true;
  if (na != nullptr) {
    q.normals = {*na, *nb, *nc, *nc};
    q.has_normals = true;
  }
  return q;
}

/// Greedy pairing of edge-adjacent triangles into convex quads (see convert_triangles_to_quads).
/// Triangles must be non-degenerate. `allow_merge` = false emits every triangle alone.
void merge_triangles(const std::vector<Vec3>& v, const std::vector<Vec3>* normals,
                     const std::vector<Tri>& tris, bool allow_merge, std::vector<ConvexQuad>& out,
                     std::size_t& quads, std::size_t& triangles) {
  const std::size_t nt = tris.size();
  std::vector<std::int64_t> partner(nt, -1);
  std::vector<std::array<std::uint32_t, 4>> quad_of(nt);  // corner indices when merged
  if (allow_merge && nt >= 2) {
    // Directed edge (a -> b) -> triangle; an undirected edge used more than twice, or twice in
    // the same direction, is not merged across.
    std::unordered_map<std::uint64_t, std::int64_t> edge_owner;
    std::unordered_map<std::uint64_t, int> edge_uses;
    auto key = [](std::uint32_t a, std::uint32_t b) {
      return (static_cast<std::uint64_t>(a) << 32) | b;
    };
    for (std::size_t t = 0; t < nt; ++t) {
      for (int k = 0; k < 3; ++k) {
        const std::uint32_t a = tris[t][static_cast<std::size_t>(k)];
        const std::uint32_t b = tris[t][static_cast<std::size_t>((k + 1) % 3)];
        edge_owner[key(a, b)] = static_cast<std::int64_t>(t);
        ++edge_uses[key(std::min(a, b), std::max(a, b))];
      }
    }
    for (std::size_t t = 0; t < nt; ++t) {
      if (partner[t] >= 0) continue;
      double best = -kInfinity;
      std::int64_t best_o = -1;
      std::array<std::uint32_t, 4> best_q{};
      for (int k = 0; k < 3; ++k) {
        const std::uint32_t s = tris[t][static_cast<std::size_t>(k)];
        const std::uint32_t e = tris[t][static_cast<std::size_t>((k + 1) % 3)];
        const std::uint32_t a = tris[t][static_cast<std::size_t>((k + 2) % 3)];
        if (edge_uses[key(std::min(s, e), std::max(s, e))] != 2) continue;
        const auto it = edge_owner.find(key(e, s));
        if (it == edge_owner.end()) continue;
        const std::int64_t o = it->second;
        if (o == static_cast<std::int64_t>(t) || partner[static_cast<std::size_t>(o)] >= 0) {
          continue;
        }
        // The other triangle's third vertex b: triangle o runs e -> s -> b.
        const Tri& to = tris[static_cast<std::size_t>(o)];
        std::uint32_t b = to[0];
        for (int j = 0; j < 3; ++j) {
          if (to[static_cast<std::size_t>(j)] == e &&
              to[static_cast<std::size_t>((j + 1) % 3)] == s) {
            b = to[static_cast<std::size_t>((j + 2) % 3)];
          }
        }
        if (b == a) continue;
        // Triangle t = (s, e, a), o = (e, s, b): the quad runs s -> b -> e -> a.
        const std::array<Vec3, 4> q = {v[s], v[b], v[e], v[a]};
        if (!acceptable_quad(q)) continue;
        const Vec3 n = glm::normalize(glm::cross(q[2] - q[0], q[3] - q[1]));
        const double quality = min_corner_sine(q, n);
        if (quality > best) {
          best = quality;
          best_o = o;
          best_q = {s, b, e, a};
        }
      }
      if (best_o >= 0) {
        partner[t] = best_o;
        partner[static_cast<std::size_t>(best_o)] = static_cast<std::int64_t>(t);
        quad_of[t] = best_q;
        quad_of[static_cast<std::size_t>(best_o)] = best_q;
      }
    }
  }
  std::vector<bool> emitted(nt, false);
  for (std::size_t t = 0; t < nt; ++t) {
    if (emitted[t]) continue;
    emitted[t] = true;
    if (partner[t] >= 0) {
      emitted[static_cast<std::size_t>(partner[t])] = true;
      ConvexQuad q;
      for (std::size_t i = 0; i < 4; ++i) {
        q.corners[i] = v[quad_of[t][i]];
        if (normals != nullptr) q.normals[i] = (*normals)[quad_of[t][i]];
      }
      q.has_normals = normals != nullptr;
      out.push_back(q);
      ++quads;
    } else {
      const Tri& tr = tris[t];
      if (normals != nullptr) {
        out.push_back(make_triangle(v[tr[0]], v[tr[1]], v[tr[2]], &(*normals)[tr[0]],
                                    &(*normals)[tr[1]], &(*normals)[tr[2]]));
      } else {
        out.push_back(make_triangle(v[tr[0]], v[tr[1]], v[tr[2]], nullptr, nullptr, nullptr));
      }
      ++triangles;
    }
  }
}

}  // namespace

std::size_t convert_polygon(const std::vector<Vec3>& vertices, const std::vector<Vec3>& normals_in,
                            std::vector<ConvexQuad>& out, ConvexQuadReport& report) {
  ++report.polygons;
  std::array<bool, static_cast<std::size_t>(PolygonRepair::kCount)> repairs{};
  auto reject = [&](PolygonRejection r) {
    ++report.rejected;
    ++report.rejections[static_cast<std::size_t>(r)];
    return std::size_t{0};
  };
  // triangulate_polygon rejects these two as well, but only with a text: checking them here
  // keeps them apart from the zero-area rejections below.
  if (vertices.size() < 3) return reject(PolygonRejection::TooFewVertices);
  for (const Vec3& p : vertices) {
    if (!is_finite(p)) return reject(PolygonRejection::NonFiniteVertex);
  }
  // Normals: one per vertex, finite and non-zero, or none. Indexed like `vertices`.
  std::vector<Vec3> nrm;
  if (!normals_in.empty()) {
    bool ok = normals_in.size() == vertices.size();
    for (std::size_t i = 0; ok && i < normals_in.size(); ++i) {
      const double l = glm::length(normals_in[i]);
      ok = std::isfinite(l) && l > 0.0;
      if (ok) nrm.push_back(normals_in[i] / l);
    }
    if (!ok) {
      nrm.clear();
      repairs[static_cast<std::size_t>(PolygonRepair::NormalsDropped)] = true;
    }
  }
  const bool has_normals = !nrm.empty();

  // The clean-up (duplicate and collinear vertices) and the ear clipping are triangulate's; its
  // triangles index `vertices`, counter-clockwise about the polygon's Newell normal. Best-shaped
  // ears: they pair up into convex quads more often than the default walk's.
  const TriangulationResult tri = triangulate_polygon(vertices, EarChoice::BestShaped);
  // An outline that crosses itself; or fewer than 3 distinct or non-collinear vertices, or no
  // area (the reason texts tell apart which; the report counts them all as zero area).
  if (tri.rejected)
    return reject(tri.not_simple ? PolygonRejection::NotSimple : PolygonRejection::ZeroArea);
  // Forced ears or triangles that do not tile the polygon: it crosses itself.
  if (tri.not_simple) return reject(PolygonRejection::NotSimple);
  if (tri.removed_duplicates > 0) {
    repairs[static_cast<std::size_t>(PolygonRepair::DuplicateVertex)] = true;
  }
  if (tri.removed_collinear > 0) {
    repairs[static_cast<std::size_t>(PolygonRepair::CollinearVertex)] = true;
  }
  // Ullner's planarity tolerance (tighter than triangulate's warning threshold); both are
  // relative to the polygon's diameter.
  const bool planar = tri.plane_deviation <= kernels::kUllnerPlanarityTolerance;
  if (!planar) repairs[static_cast<std::size_t>(PolygonRepair::NonPlanar)] = true;

  // A polygon left with 3 or 4 vertices: its outline is the vertices its triangles use, in
  // input order (triangulate removes vertices but never reorders them).
  std::vector<std::uint32_t> outline;
  if (tri.triangles.size() <= 2) {
    for (const Tri& t : tri.triangles) outline.insert(outline.end(), t.begin(), t.end());
    std::sort(outline.begin(), outline.end());
    outline.erase(std::unique(outline.begin(), outline.end()), outline.end());
  }
  auto corner = [&](std::size_t i) { return vertices[outline[i]]; };
  auto normal_of = [&](std::size_t i) { return nrm[outline[i]]; };

  std::size_t quads = 0, tris = 0;
  const std::size_t before = out.size();
  if (outline.size() == 4 && planar &&
      acceptable_quad({corner(0), corner(1), corner(2), corner(3)})) {
    // A convex quad as given keeps its vertex order: p00 = first vertex (u, v follow the file).
    ConvexQuad q;
    q.corners = {corner(0), corner(1), corner(2), corner(3)};
    if (has_normals) q.normals = {normal_of(0), normal_of(1), normal_of(2), normal_of(3)};
    q.has_normals = has_normals;
    out.push_back(q);
    quads = 1;
  } else if (outline.size() == 3) {
    // A triangle likewise keeps its order: p00 = first vertex, p11 = p01 = last.
    if (has_normals) {
      const Vec3 n0 = normal_of(0), n1 = normal_of(1), n2 = normal_of(2);
      out.push_back(make_triangle(corner(0), corner(1), corner(2), &n0, &n1, &n2));
    } else {
      out.push_back(make_triangle(corner(0), corner(1), corner(2), nullptr, nullptr, nullptr));
    }
    tris = 1;
  } else {
    merge_triangles(vertices, has_normals ? &nrm : nullptr, tri.triangles, planar, out, quads,
                    tris);
  }
  ++report.converted;
  bool any = false;
  for (std::size_t i = 0; i < repairs.size(); ++i) {
    if (repairs[i]) {
      ++report.repairs[i];
      any = true;
    }
  }
  if (any) ++report.repaired;
  report.quads += quads;
  report.triangles += tris;
  return out.size() - before;
}

std::vector<ConvexQuad> convert_polygon(const std::vector<Vec3>& vertices,
                                        const std::vector<Vec3>& normals,
                                        ConvexQuadReport& report) {
  std::vector<ConvexQuad> out;
  convert_polygon(vertices, normals, out, report);
  return out;
}

std::vector<ConvexQuad> convert_triangles_to_quads(const std::vector<Vec3>& vertices,
                                                   const std::vector<Tri>& triangles,
                                                   const std::vector<Vec3>& normals,
                                                   ConvexQuadReport* report) {
  ConvexQuadReport local;
  ConvexQuadReport& rep = report != nullptr ? *report : local;
  const bool has_normals = !normals.empty() && normals.size() == vertices.size();
  std::vector<Vec3> nrm;
  if (has_normals) {
    nrm.resize(normals.size());
    for (std::size_t i = 0; i < normals.size(); ++i) {
      const double l = glm::length(normals[i]);
      nrm[i] = (l > 0.0 && std::isfinite(l)) ? normals[i] / l : Vec3(0.0);
    }
  }
  // Drop degenerate triangles (out-of-range index, non-finite, zero area).
  std::vector<Tri> good;
  good.reserve(triangles.size());
  for (const Tri& t : triangles) {
    bool ok = t[0] < vertices.size() && t[1] < vertices.size() && t[2] < vertices.size();
    if (ok) {
      const Vec3 &a = vertices[t[0]], &b = vertices[t[1]], &c = vertices[t[2]];
      const double l = std::max({glm::length(b - a), glm::length(c - b), glm::length(a - c)});
      ok = is_finite(a) && is_finite(b) && is_finite(c) &&
           glm::length(glm::cross(b - a, c - a)) > kernels::kUllnerMinRelativeArea * l * l;
    }
    if (ok) {
      good.push_back(t);
    } else {
      ++rep.triangles_dropped;
    }
  }
  std::vector<ConvexQuad> out;
  merge_triangles(vertices, has_normals ? &nrm : nullptr, good, true, out, rep.quads,
                  rep.triangles);
  // A zero normal supplied for a vertex leaves that primitive without normals.
  for (ConvexQuad& q : out) {
    if (!q.has_normals) continue;
    for (const Vec3& m : q.normals) {
      if (m == Vec3(0.0)) q.has_normals = false;
    }
  }
  return out;
}

}  // namespace rtsim::geometry
