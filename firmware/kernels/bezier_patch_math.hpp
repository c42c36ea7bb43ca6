#pragma once
// Bicubic Bezier patch algebra for Wang, Lewis & Hung's ray/patch pipeline (seed 002 §2.2, §2.4,
// §2.6) and for the double-precision reference solver: the control net, the de Casteljau
// subdivision matrices D^L, D^R, D^T, D^B (eqs. 7-11), the parametric centre Q(1/2,1/2) (eqs.
// 17-18), evaluation, partial derivatives and the surface normal.
//
// Orientation. The paper writes the patch twice and the two forms disagree: eq. 2 (seed 002 L106)
// pairs the column index j of P_ij with u, while the matrix form Q = U M P M^t V (eq. 4, L116)
// multiplies the ROWS of P by the u-basis. We store the net in the orientation of eq. 4 (so that
// the paper's D^L P and P D^T read verbatim) and keep the meaning of u from eq. 2 and from
// scenes::BezierPatch (row i = v, column j = u): ControlNet::p[a][b] = BezierPatch::at(b, a).
// Hence the u of every SurfaceHit is the parameter along a row of the .bpt file.
#include <array>
#include <cmath>
#include <cstdint>

#include "firmware/bounds.hpp"
#include "firmware/math.hpp"
#include "firmware/scene.hpp"

namespace rtsim::kernels {

/// 16 control points in the orientation of eq. 4: p[a][b], a = u index (row), b = v index.
template <typename T>
struct ControlNet {
  std::array<std::array<Vec3T<T>, 4>, 4> p{};
};

/// A subdivision matrix stored as integer eighths: the paper's D = (1/8) * eighths (eqs. 7-10).
using Eighths4 = std::array<std::array<int, 4>, 4>;

/// D^L, eq. 7 (seed 002 L151): P^L = D^L P gives Q^L(u,v) = Q(u/2, v).
inline constexpr Eighths4 kDL = {{{8, 0, 0, 0}, {4, 4, 0, 0}, {2, 4, 2, 0}, {1, 3, 3, 1}}};
/// D^R, eq. 9 (L159): P^R = D^R P gives Q^R(u,v) = Q((u+1)/2, v).
inline constexpr Eighths4 kDR = {{{1, 3, 3, 1}, {0, 2, 4, 2}, {0, 0, 4, 4}, {0, 0, 0, 8}}};
/// D^T = (D^L)^t, eq. 10 (L163): P^T = P' D^T gives Q(u, v/2) (the first half in v).
inline constexpr Eighths4 kDT = {{{8, 4, 2, 1}, {0, 4, 4, 3}, {0, 0, 2, 3}, {0, 0, 0, 1}}};
/// D^B = (D^R)^t, eq. 10 (L163): P^B = P' D^B gives Q(u, (v+1)/2) (the second half in v).
inline constexpr Eighths4 kDB = {{{1, 0, 0, 0}, {3, 2, 0, 0}, {3, 4, 4, 0}, {1, 2, 4, 8}}};

/// Literal matrix product (1/8) D P (eqs. 7, 9). Reference form, used by the tests; the pipeline
/// uses split_u, which computes D^L P and D^R P together.
template <typename T>
ControlNet<T> left_multiply(const Eighths4& d, const ControlNet<T>& net) {
  ControlNet<T> out;
  for (int r = 0; r < 4; ++r)
    for (int c = 0; c < 4; ++c) {
      Vec3T<T> s(T(0));
      for (int k = 0; k < 4; ++k) s += T(d[r][k]) * net.p[k][c];
      out.p[r][c] = s * T(0.125);
    }
  return out;
}

/// Literal matrix product (1/8) P D (eq. 10).
template <typename T>
ControlNet<T> right_multiply(const ControlNet<T>& net, const Eighths4& d) {
  ControlNet<T> out;
  for (int r = 0; r < 4; ++r)
    for (int c = 0; c < 4; ++c) {
      Vec3T<T> s(T(0));
      for (int k = 0; k < 4; ++k) s += net.p[r][k] * T(d[k][c]);
      out.p[r][c] = s * T(0.125);
    }
  return out;
}

/// One cubic split at 1/2 of the four points q0..q3: left = rows of D^L applied to q, right = rows
/// of D^R. The de Casteljau midpoints share the partial sums of the two products: D^L row 2,
/// (2,4,2,0)/8, is the mean of the first two midpoints, D^L row 3 = D^R row 0, (1,3,3,1)/8, is the
/// mean of those two means, and so on. Cost per coordinate: 6 additions, 6 halvings.
template <typename T>
inline void split_cubic(const Vec3T<T>& q0, const Vec3T<T>& q1, const Vec3T<T>& q2,
                        const Vec3T<T>& q3, Vec3T<T> left[4], Vec3T<T> right[4]) {
  const T h = T(0.5);
  const Vec3T<T> m01 = (q0 + q1) * h, m12 = (q1 + q2) * h, m23 = (q2 + q3) * h;
  const Vec3T<T> m012 = (m01 + m12) * h, m123 = (m12 + m23) * h;
  const Vec3T<T> mid = (m012 + m123) * h;
  left[0] = q0;
  left[1] = m01;
  left[2] = m012;
  left[3] = mid;
  right[0] = mid;
  right[1] = m123;
  right[2] = m23;
  right[3] = q3;
}

/// u-split, step 1 of §2.4 (L141-L159): left = D^L P, right = D^R P (each column b separately).
template <typename T>
inline void split_u(const ControlNet<T>& net, ControlNet<T>& left, ControlNet<T>& right) {
  for (int b = 0; b < 4; ++b) {
    Vec3T<T> l[4], r[4];
    split_cubic(net.p[0][b], net.p[1][b], net.p[2][b], net.p[3][b], l, r);
    for (int a = 0; a < 4; ++a) {
      left.p[a][b] = l[a];
      right.p[a][b] = r[a];
    }
  }
}

/// v-split, step 2 of §2.4 (L161-L163): top = P D^T, bottom = P D^B (each row a separately).
template <typename T>
inline void split_v(const ControlNet<T>& net, ControlNet<T>& top, ControlNet<T>& bottom) {
  for (int a = 0; a < 4; ++a) {
    Vec3T<T> l[4], r[4];
    split_cubic(net.p[a][0], net.p[a][1], net.p[a][2], net.p[a][3], l, r);
    for (int b = 0; b < 4; ++b) {
      top.p[a][b] = l[b];
      bottom.p[a][b] = r[b];
    }
  }
}

/// Index of a quadrant in a four-way split, eq. 11 (L167): [[TL, TR], [BL, BR]].
/// T/B is the first/second half in v, L/R the first/second half in u.
enum Quadrant : int { kTL = 0, kTR = 1, kBL = 2, kBR = 3 };
inline constexpr int quadrant_u_half(int q) { return q & 1; }
inline constexpr int quadrant_v_half(int q) { return q >> 1; }

/// Four-way split, eq. 11: out[kTL] = D^L P D^T, out[kTR] = D^R P D^T, out[kBL] = D^L P D^B,
/// out[kBR] = D^R P D^B. (As printed, eq. 11's block dimensions do not conform; this is the
/// intended meaning, see note 002 §2.3.)
template <typename T>
inline void split4(const ControlNet<T>& net, ControlNet<T> out[4]) {
  ControlNet<T> left, right;
  split_u(net, left, right);
  split_v(left, out[kTL], out[kBL]);
  split_v(right, out[kTR], out[kBR]);
}

/// Parametric centre C = Q(1/2, 1/2) = (1/64) [1 3 3 1] P [1 3 3 1]^t, eqs. 17-18 (L217-L221).
/// Cost per coordinate: 4 column sums c_b = p0b + 3 p1b + 3 p2b + p3b (2 mul, 3 add each), the
/// same weighted sum over the four c_b (2 mul, 3 add), times 1/64 (1 mul): 11 mul, 15 add.
template <typename T>
inline Vec3T<T> parametric_center(const ControlNet<T>& net) {
  Vec3T<T> c[4];
  for (int b = 0; b < 4; ++b)
    c[b] = net.p[0][b] + T(3) * net.p[1][b] + T(3) * net.p[2][b] + net.p[3][b];
  return (c[0] + T(3) * c[1] + T(3) * c[2] + c[3]) * T(1.0 / 64.0);
}

/// Cubic Bernstein basis B_{k,3}(s), eq. 3 (L112), k = 0..3.
template <typename T>
inline std::array<T, 4> bernstein3(T s) {
  const T r = T(1) - s;
  return {r * r * r, T(3) * s * r * r, T(3) * s * s * r, s * s * s};
}

/// Quadratic Bernstein basis B_{k,2}(s), for the derivatives.
template <typename T>
inline std::array<T, 3> bernstein2(T s) {
  const T r = T(1) - s;
  return {r * r, T(2) * s * r, s * s};
}

/// Q(u, v), eq. 2 / eq. 4.
template <typename T>
Vec3T<T> evaluate(const ControlNet<T>& net, T u, T v) {
  const auto bu = bernstein3(u), bv = bernstein3(v);
  Vec3T<T> q(T(0));
  for (int a = 0; a < 4; ++a) {
    Vec3T<T> row(T(0));
    for (int b = 0; b < 4; ++b) row += bv[b] * net.p[a][b];
    q += bu[a] * row;
  }
  return q;
}

/// Q and its partial derivatives Q_u, Q_v at (u, v) (derivative of a Bernstein sum: 3 times the
/// quadratic sum of forward differences).
template <typename T>
void evaluate_with_derivatives(const ControlNet<T>& net, T u, T v, Vec3T<T>& q, Vec3T<T>& qu,
                               Vec3T<T>& qv) {
  const auto bu = bernstein3(u), bv = bernstein3(v);
  const auto du = bernstein2(u), dv = bernstein2(v);
  q = qu = qv = Vec3T<T>(T(0));
  for (int a = 0; a < 4; ++a)
    for (int b = 0; b < 4; ++b) q += (bu[a] * bv[b]) * net.p[a][b];
  for (int a = 0; a < 3; ++a)
    for (int b = 0; b < 4; ++b) qu += (du[a] * bv[b]) * (net.p[a + 1][b] - net.p[a][b]);
  for (int a = 0; a < 4; ++a)
    for (int b = 0; b < 3; ++b) qv += (bu[a] * dv[b]) * (net.p[a][b + 1] - net.p[a][b]);
  qu *= T(3);
  qv *= T(3);
}

/// Unit normal Q_u x Q_v at (u, v) of a double-precision net. Where the patch is degenerate (the
/// teapot's lid and bottom collapse a whole edge to a point, so Q_u or Q_v vanishes there) the
/// normal is taken a little further inside the patch, toward (1/2, 1/2): first by
/// kNormalNudge[0] in parameter, then larger. Returns false if no usable normal exists (a patch
/// collapsed to a curve or a point).
bool patch_normal(const ControlNet<double>& net, double u, double v, Vec3& normal);

/// Axis-aligned box of the 16 control points: it contains the patch (convex-hull property, L80).
template <typename T>
Bounds control_bounds(const ControlNet<T>& net) {
  Bounds b;
  for (const auto& row : net.p)
    for (const auto& q : row) b.extend(Vec3(q));
  return b;
}

template <typename T>
bool is_finite_net(const ControlNet<T>& net) {
  for (const auto& row : net.p)
    for (const auto& q : row)
      if (!std::isfinite(q.x) || !std::isfinite(q.y) || !std::isfinite(q.z)) return false;
  return true;
}

/// From the scene model (row i = v, column j = u) to the eq.-4 orientation (transpose).
ControlNet<double> control_net_from(const scenes::BezierPatch& patch);

/// Precision change of a whole net (the DSP pipeline holds IEEE single, seed 002 L296).
template <typename T, typename S>
ControlNet<T> convert_net(const ControlNet<S>& net) {
  ControlNet<T> out;
  for (int a = 0; a < 4; ++a)
    for (int b = 0; b < 4; ++b) out.p[a][b] = Vec3T<T>(net.p[a][b]);
  return out;
}

}  // namespace rtsim::kernels
