// The contact solver (docs/contacts.md): a velocity-level impulse at a contact point with Newton
// restitution e and Coulomb friction mu, applied through the body's generalized 6x6 mass (body
// plus added mass), and a position correction that leaves the velocities alone; contact_resolve
// takes all the touching points of a body at once.
//
// Written once: kernels on plain numbers of type T (double on the scalar step, double or float
// in the batched loops). Everything here is in the BODY frame (axes of the shape, origin at the
// centre of mass), as the state's v and w and the model's M^-1 are: the caller turns the wall's
// normal into the body frame and the position correction back into the world frame.
//
// Called after each step by the contact pass (contact/pass.h; the scalar step and the batched
// steps alike, for bodies near a surface), with the scene's ground.contact / walls.contact
// "collide".
#pragma once
#include <algorithm>
#include <cmath>

#include "contact/points.h"
#include "util/lane.h"
#include "util/types.h"

namespace lrigid {
// Is the 6x6 inverse mass Minv (row-major) diagonal? (boxes, ellipsoids and spheres with the
// centre of mass at the centroid: BodyType::M_diagonal). contact_resolve then multiplies by its
// diagonal only: the same numbers, a sixth of the products.
template <typename T>
bool inverse_mass_is_diagonal(const T* Minv) {
  for (int i = 0; i < 6; ++i)
    for (int j = 0; j < 6; ++j)
      if (i != j && Minv[6 * i + j] != T(0)) return false;
  return true;
}

// The velocity change of the contact point r (body frame, from the centre of mass) and of the
// body (dv, dw) when the impulse J (N s, body frame) acts at r: dxi = M^-1 [J; r x J],
// dvc = dv + dw x r. Minv: the 6x6 generalized inverse mass [v; w], row-major (symmetric);
// diagonal: Minv is diagonal (inverse_mass_is_diagonal), only its diagonal is read.
template <typename T>
LRIGID_LANE void contact_response(const T* Minv, const T* r, const T* J, T* dvc, T* dv, T* dw,
                                  bool diagonal = false) {
  T p[6];
  p[0] = J[0], p[1] = J[1], p[2] = J[2];
  cross3(r, J, p + 3);
  T d[6];
  if (diagonal) {
#pragma GCC unroll 6
    for (int i = 0; i < 6; ++i) d[i] = Minv[7 * i] * p[i];
  } else {
#pragma GCC unroll 6
    for (int i = 0; i < 6; ++i) {
      T s = T(0);
#pragma GCC unroll 6
      for (int j = 0; j < 6; ++j) s += Minv[6 * i + j] * p[j];
      d[i] = s;
    }
  }
  dv[0] = d[0], dv[1] = d[1], dv[2] = d[2];
  dw[0] = d[3], dw[1] = d[4], dw[2] = d[5];
  T wxr[3];
  cross3(dw, r, wxr);
#pragma GCC unroll 3
  for (int a = 0; a < 3; ++a) dvc[a] = dv[a] + wxr[a];
}

// The velocity change of the body (dv, dw; body frame) when the angular impulse L (N m s, body
// frame) acts on it: [dv; dw] = M^-1 [0; L] (dv is 0 unless M couples the directions).
template <typename T>
LRIGID_LANE void torque_response(const T* Minv, const T* L, T* dv, T* dw, bool diagonal = false) {
#pragma GCC unroll 3
  for (int i = 0; i < 3; ++i) {
    T sv = T(0), sw = T(0);
#pragma GCC unroll 3
    for (int j = 0; j < 3; ++j) {
      sv += diagonal ? T(0) : Minv[6 * i + 3 + j] * L[j];
      sw += (diagonal && i != j) ? T(0) : Minv[6 * (3 + i) + 3 + j] * L[j];
    }
    dv[i] = sv, dw[i] = sw;
  }
}

// Rolling resistance at one touching point (docs/contacts.md "Rolling resistance"): the
// surface resists the body's rotation relative to it -- its rolling (the spin perpendicular to
// the normal) and its twisting (the spin about the normal), as LIGGGHTS' constant directional
// torque model with torsionTorque on -- with a torque of at most mu_r |r| N (N the normal
// force, r the point's offset from the centre of mass): over a step, an angular impulse of at
// most cap = mu_r |r| J_n. L is the point's accumulated angular impulse so far (body frame); it
// becomes L - lambda a, a = w / |w|, with lambda = |w| / (a.W a) the impulse that stops the
// rotation along a (W the angular block of M^-1), scaled back onto |L| <= cap (Coulomb-like: it
// stops the rotation, or slows it by what the cap allows, and never reverses it). dL receives
// the change of L, for the caller to apply (torque_response).
template <typename T>
LRIGID_LANE void rolling_resistance_impulse(const T* Minv, const T* w, T cap, T* L, T* dL) {
  const T* wt = w;
  const T spin = std::sqrt(dot3(wt, wt));
  const T inv = T(1) / (spin > T(0) ? spin : T(1));
  T axis[3], Wa[3];
#pragma GCC unroll 3
  for (int a = 0; a < 3; ++a) axis[a] = wt[a] * inv;
#pragma GCC unroll 3
  for (int i = 0; i < 3; ++i) {
    T s = T(0);
#pragma GCC unroll 3
    for (int j = 0; j < 3; ++j) s += Minv[6 * (3 + i) + 3 + j] * axis[j];
    Wa[i] = s;
  }
  const T waa = dot3(axis, Wa);
  const T lambda = spin > T(0) ? spin / waa : T(0);
  T Ln[3];
#pragma GCC unroll 3
  for (int a = 0; a < 3; ++a) Ln[a] = L[a] - lambda * axis[a];
  const T norm = std::sqrt(dot3(Ln, Ln));
  const T clip = norm > cap ? cap / norm : T(1);
#pragma GCC unroll 3
  for (int a = 0; a < 3; ++a) {
    Ln[a] *= clip;
    dL[a] = Ln[a] - L[a];
    L[a] = Ln[a];
  }
}

// x = K^-1 b for a 3x3 K (row-major) by its adjugate.
template <typename T>
LRIGID_LANE void solve3(const T* K, const T* b, T* x) {
  const T det = K[0] * (K[4] * K[8] - K[5] * K[7]) - K[1] * (K[3] * K[8] - K[5] * K[6]) +
                K[2] * (K[3] * K[7] - K[4] * K[6]);
  const T idet = T(1) / det;
  const T Ki[9] = {(K[4] * K[8] - K[5] * K[7]) * idet, (K[2] * K[7] - K[1] * K[8]) * idet,
                   (K[1] * K[5] - K[2] * K[4]) * idet, (K[5] * K[6] - K[3] * K[8]) * idet,
                   (K[0] * K[8] - K[2] * K[6]) * idet, (K[2] * K[3] - K[0] * K[5]) * idet,
                   (K[3] * K[7] - K[4] * K[6]) * idet, (K[1] * K[6] - K[0] * K[7]) * idet,
                   (K[0] * K[4] - K[1] * K[3]) * idet};
  mul(Ki, b, x);
}

// What one contact does to a body.
template <typename T>
struct ContactOut {
  T J[3];        // impulse at the contact point, body frame, N s
  T dv[3];       // change of the centre of mass's velocity, body frame, m/s
  T dw[3];       // change of the angular velocity, body frame, rad/s
  T jn;          // normal impulse J.n (>= 0), N s
  T jt;          // tangential impulse |J - jn n| (<= mu jn), N s
  T dx[3];       // position correction of the centre of mass, body frame (depth n), m
  T active;      // 1 when an impulse was applied, 0 otherwise
};

// One contact point: r (body frame, from the centre of mass), the wall's unit normal n (body
// frame, pointing from the wall into the fluid), the penetration depth (m, = -wall distance of
// the point; the point touches the wall when depth >= 0) and the body's velocity v and spin w
// (body frame). The impulse acts when the point touches and approaches (v_n < 0): it brings
// the point's normal velocity to vn_target (>= 0; -e v_n for one point alone, see
// contact_kernel), at most -v_n (never a faster rebound than an elastic one), and its
// tangential velocity to 0 when the needed impulse lies in the friction cone
// |J_t| <= mu J_n (sticking); otherwise it slides: J = j_n (n - mu t), t the unit slip
// velocity before the contact, |J_t| = mu J_n exactly. An impulse that would raise the
// kinetic energy (possible with friction when M couples the directions) is replaced by the
// frictionless one, which never does. The position correction moves the body out along n by
// the depth and leaves the velocities alone (no Baumgarte feedback): it adds no kinetic energy.
template <typename T>
LRIGID_LANE ContactOut<T> contact_impulse_kernel(const ContactParams& k, const T* Minv,
                                                 const T* v, const T* w, const T* r, const T* n,
                                                 T depth, T vn_target) {
  ContactOut<T> o;
  const T mu = T(k.friction);
  // velocity of the contact point and its normal and tangential parts
  T wxr[3], vc[3];
  cross3(w, r, wxr);
#pragma GCC unroll 3
  for (int a = 0; a < 3; ++a) vc[a] = v[a] + wxr[a];
  const T vn = dot3(vc, n);
  T vt[3];
#pragma GCC unroll 3
  for (int a = 0; a < 3; ++a) vt[a] = vc[a] - vn * n[a];
  const T vt_norm = std::sqrt(dot3(vt, vt));
  // K: the contact point's velocity change per unit impulse (symmetric positive definite)
  T K[9], dv[3], dw[3];
#pragma GCC unroll 3
  for (int j = 0; j < 3; ++j) {
    const T ej[3] = {T(j == 0), T(j == 1), T(j == 2)};
    T col[3];
    contact_response(Minv, r, ej, col, dv, dw);
    K[j] = col[0], K[3 + j] = col[1], K[6 + j] = col[2];
  }
  T Kn[3];
  mul(K, n, Kn);
  const T knn = dot3(n, Kn);
  // the normal velocity wanted after the contact: at most the elastic rebound
  const T vn_after = vn_target < -vn ? vn_target : -vn;
  const T dvn = vn_after - vn;  // > 0 when active
  // frictionless: J = j0 n
  const T j0 = dvn / knn;
  // sticking: K J = dvn n - vt
  T want[3], Js[3];
#pragma GCC unroll 3
  for (int a = 0; a < 3; ++a) want[a] = dvn * n[a] - vt[a];
  solve3(K, want, Js);
  const T jn_s = dot3(Js, n);
  T Jst[3];
#pragma GCC unroll 3
  for (int a = 0; a < 3; ++a) Jst[a] = Js[a] - jn_s * n[a];
  const T jt_s = std::sqrt(dot3(Jst, Jst));
  const bool sticks = jt_s <= mu * jn_s;
  // sliding: J = j_d (n - mu t), t = vt / |vt|
  const T inv_vt = T(1) / (vt_norm > T(0) ? vt_norm : T(1));
  T d[3];
#pragma GCC unroll 3
  for (int a = 0; a < 3; ++a) d[a] = n[a] - mu * vt[a] * inv_vt;
  T Kd[3];
  mul(K, d, Kd);
  const T den = dot3(n, Kd);
  const bool slide_ok = (vt_norm > T(0)) & (den > T(1e-6) * knn);
  const T jd = dvn / (slide_ok ? den : T(1));
  T J[3];
#pragma GCC unroll 3
  for (int a = 0; a < 3; ++a) J[a] = sticks ? Js[a] : (slide_ok ? jd * d[a] : j0 * n[a]);
  // the kinetic energy change J.vc + J.K J / 2 must not be positive
  T KJ[3];
  mul(K, J, KJ);
  const T dE = dot3(J, vc) + T(0.5) * dot3(J, KJ);
  const bool gains = dE > T(0);
  const bool active = (depth >= T(0)) & (vn < T(0)) & (dvn > T(0));
#pragma GCC unroll 3
  for (int a = 0; a < 3; ++a) {
    J[a] = gains ? j0 * n[a] : J[a];
    J[a] = active ? J[a] : T(0);
    o.J[a] = J[a];
  }
  T dvc[3];
  contact_response(Minv, r, J, dvc, o.dv, o.dw);
  o.jn = dot3(J, n);
  T Jt[3];
#pragma GCC unroll 3
  for (int a = 0; a < 3; ++a) Jt[a] = J[a] - o.jn * n[a];
  o.jt = std::sqrt(dot3(Jt, Jt));
  const T dpos = depth > T(0) ? depth : T(0);
#pragma GCC unroll 3
  for (int a = 0; a < 3; ++a) o.dx[a] = dpos * n[a];
  o.active = active ? T(1) : T(0);
  return o;
}

// One contact point alone: the normal velocity after is -e times the one before.
template <typename T>
LRIGID_LANE ContactOut<T> contact_kernel(const ContactParams& k, const T* Minv, const T* v,
                                         const T* w, const T* r, const T* n, T depth) {
  T wxr[3], vc[3];
  cross3(w, r, wxr);
#pragma GCC unroll 3
  for (int a = 0; a < 3; ++a) vc[a] = v[a] + wxr[a];
  const T vn = dot3(vc, n);
  return contact_impulse_kernel(k, Minv, v, w, r, n, depth, -T(k.restitution) * vn);
}

// The impulse (P, N s) and angular impulse (L, N m s; body frame, about the centre of mass)
// that stop a body moving with (v, w): [P; L] = -M [v; w], M the 6x6 generalized mass, row-major.
template <typename T>
void stopping_impulse(const T* M, const T* v, const T* w, T* P, T* L) {
  for (int i = 0; i < 3; ++i) {
    T sp = T(0), sl = T(0);
    for (int j = 0; j < 3; ++j) {
      sp += M[6 * i + j] * v[j] + M[6 * i + 3 + j] * w[j];
      sl += M[6 * (3 + i) + j] * v[j] + M[6 * (3 + i) + 3 + j] * w[j];
    }
    P[i] = -sp, L[i] = -sl;
  }
}

// A body lying on one plane: its touching points r_i (body frame, m of them) share the unit
// normal n (body frame, from the surface into the fluid) and each approaches slower than
// k.rest_speed, so contact_resolve's target normal velocity of each is 0. The impulse that stops
// the body, [P; L] = -M [v; w] (M the 6x6 generalized mass, row-major, symmetric), is one the
// points can give -- normal impulses >= 0, each point's impulse inside its friction cone -- when
//  1. it presses: P_n = P.n > 0;
//  2. its centre of pressure lies in a triangle of three touching points: the point c of the
//     contact plane with L = c x P + tau n (tau: the moment about the normal),
//     c = h n + n x (L - h n x P) / P_n, h the points' mean offset along n;
//  3. each of those three points, carrying lambda_i P (lambda_i: c's barycentric weight) plus its
//     share lambda_i kappa n x d_i of the couple tau (d_i: from c to the point in the plane;
//     kappa = tau / sum_j lambda_j |d_j|^2; the couple adds no force), stays in its cone:
//     |P_t| + |kappa| |d_i| <= mu P_n.
// Then v = w = 0 is a solution of the contact problem (every point sticks, no point moves along
// the normal, no normal impulse pulls): where contact_resolve's sweeps converge for a body at
// rest, taken at once (a resting box: 1/30 of the sweeps' instructions, docs/contacts.md). The
// points' offsets along n differ by the body's tilt on the plane (the depths, below a
// millimetre): the certificate neglects that difference's moment, it decides only whether the
// exact solution v = w = 0 is taken. Returns the points that carry (3), or 0 when the
// certificate fails (v, w untouched: the sweeps decide).
constexpr int kContactRestPoints = 8;  // more touching points: the sweeps
template <typename T>
int contact_rest(const ContactParams& k, const T* M, T* v, T* w, int m, const T* r, const T* n) {
  if (m < 3 || m > kContactRestPoints) return 0;
  T P[3], L[3];
  stopping_impulse(M, v, w, P, L);
  const T pn = dot3(P, n);
  if (!(pn > T(0))) return 0;
  T Pt[3];
  for (int a = 0; a < 3; ++a) Pt[a] = P[a] - pn * n[a];
  const T mu = T(k.friction), pt = std::sqrt(dot3(Pt, Pt));
  if (!(pt <= mu * pn)) return 0;
  // the points in the plane, and their mean offset along n
  T p[kContactRestPoints][3], h = T(0);
  for (int i = 0; i < m; ++i) {
    const T o = dot3(r + 3 * i, n);
    h += o;
    for (int a = 0; a < 3; ++a) p[i][a] = r[3 * i + a] - o * n[a];
  }
  h /= T(m);
  // the centre of pressure in the plane and the moment about the normal
  T nxP[3], Q[3], c[3], cxP[3];
  cross3(n, P, nxP);
  for (int a = 0; a < 3; ++a) Q[a] = L[a] - h * nxP[a];
  cross3(n, Q, c);
  for (int a = 0; a < 3; ++a) c[a] /= pn;
  T cf[3];
  for (int a = 0; a < 3; ++a) cf[a] = c[a] + h * n[a];
  cross3(cf, P, cxP);
  const T tau = dot3(L, n) - dot3(cxP, n);
  // n . ((b - a) x (d - a)) for points in the plane: twice the signed area
  auto area = [&](const T* a, const T* b, const T* d) {
    T ab[3], ad[3], x[3];
    for (int e = 0; e < 3; ++e) ab[e] = b[e] - a[e], ad[e] = d[e] - a[e];
    cross3(ab, ad, x);
    return dot3(x, n);
  };
  for (int i = 0; i < m; ++i)
    for (int j = i + 1; j < m; ++j)
      for (int l = j + 1; l < m; ++l) {
        const T A = area(p[i], p[j], p[l]);
        if (!(std::abs(A) > T(0))) continue;  // three points on a line
        const T lam[3] = {area(c, p[j], p[l]) / A, area(p[i], c, p[l]) / A,
                          area(p[i], p[j], c) / A};
        if (!(lam[0] >= T(0) && lam[1] >= T(0) && lam[2] >= T(0))) continue;
        const int idx[3] = {i, j, l};
        T d2[3], S = T(0);
        for (int q = 0; q < 3; ++q) {
          T d[3];
          for (int a = 0; a < 3; ++a) d[a] = p[idx[q]][a] - c[a];
          d2[q] = dot3(d, d);
          S += lam[q] * d2[q];
        }
        const T kappa = S > T(0) ? std::abs(tau) / S : (tau == T(0) ? T(0) : T(HUGE_VAL));
        bool holds = true;
        for (int q = 0; q < 3 && holds; ++q)
          holds = lam[q] == T(0) || pt + kappa * std::sqrt(d2[q]) <= mu * pn;
        if (!holds) continue;
        for (int a = 0; a < 3; ++a) v[a] = T(0), w[a] = T(0);
        return 3;
      }
  return 0;
}

// One point's share of a projected Gauss-Seidel sweep, written once for a body against a surface
// (contact_resolve) and for two bodies against each other (contact/island.h): the normal impulse
// that brings the point's normal velocity to `target`, the accumulated normal impulse *Jn kept
// >= 0 (points never pull); then, with `rolls`, roll(*Jn), the rolling resistance's share
// (returns its impulse change, N s); then the friction impulse along the slip v_t that would
// stop it (effective mass 1 / t.K t, t = v_t / |v_t|: the impulse (|v_t|^2 / v_t.K v_t) v_t
// against it, one division and no square root on the way), the accumulated tangential impulse
// Jt[3] kept within the cone |Jt| <= mu Jn. K: the point's 3x3 velocity change per unit impulse,
// Kn = K n, inv_knn = 1 / n.K n. vel(vc) gives the point's (relative) velocity now,
// apply_n(dj) applies the impulse dj n at the point and apply(J) the impulse J (the velocity
// after the normal impulse is the one before plus dj Kn: one vel() a sweep without rolling).
// *scale becomes at least the new normal impulse; returns the largest impulse change of the
// point.
template <typename T, class Vel, class ApplyN, class Apply, class Roll>
T contact_point_sweep(const T* K, const T* Kn, const T* n, T target, T inv_knn, T mu, bool rolls,
                      T* Jn, T* Jt, T* scale, Vel vel, ApplyN apply_n, Apply apply, Roll roll) {
  T vc[3];
  vel(vc);
  const T jn_new = std::max(T(0), *Jn + (target - dot3(vc, n)) * inv_knn);
  const T dn = jn_new - *Jn;
  T change = std::abs(dn);
  *scale = std::max(*scale, jn_new);
  *Jn = jn_new;
  apply_n(dn);
  if (rolls) {
    change = std::max(change, roll(*Jn));
    vel(vc);
  } else {
    for (int a = 0; a < 3; ++a) vc[a] += dn * Kn[a];
  }
  const T vn = dot3(vc, n);
  T vt[3];
  for (int a = 0; a < 3; ++a) vt[a] = vc[a] - vn * n[a];
  T Kv[3];
  mul(K, vt, Kv);
  const T s2 = dot3(vt, vt), den = dot3(vt, Kv);
  if (!(s2 > T(0)) || !(den > T(0))) return change;
  const T f = -s2 / den;
  T Jt_new[3];
  for (int a = 0; a < 3; ++a) Jt_new[a] = Jt[a] + f * vt[a];
  const T norm2 = dot3(Jt_new, Jt_new), cap = mu * *Jn;
  if (norm2 > cap * cap) {
    const T clip = cap / std::sqrt(norm2);
    for (int a = 0; a < 3; ++a) Jt_new[a] *= clip;
  }
  T J[3];
  for (int a = 0; a < 3; ++a) {
    J[a] = Jt_new[a] - Jt[a];
    Jt[a] = Jt_new[a];
  }
  change = std::max(change, std::sqrt(dot3(J, J)));
  apply(J);
  return change;
}

// Several contact points touching at once (a box flat on the ground, a plate across a roof
// edge): projected Gauss-Seidel on the accumulated impulses (Catto's sequential impulses),
// at most `passes` sweeps over the points (fewer once converged, kContactTolerance). Each sweep gives point i first the normal impulse change
// that brings its normal velocity to target_i -- -e times its normal velocity before the first
// sweep, 0 when it approached slower than k.rest_speed -- with the accumulated normal impulse
// kept >= 0 (points never pull); then the friction impulse along its slip velocity that would
// stop it (effective mass 1 / t.K t), with the accumulated tangential impulse scaled back onto
// the cone |J_t| <= mu J_n. Normal and friction impulses are solved one after the other, so a
// sliding point's friction is mu J_n against its slip exactly (a 3x3 solve with a radial
// projection of the coupled impulse would lose part of it to the rotation coupling). Points
// with depth < 0 (not touching) take none, unless horizon > 0 (s): then they are speculative
// points, off the surface by -depth, whose target normal velocity is depth / horizon (they may
// approach as fast as closes the gap in that time, no faster: a body lying on a surface has
// all its near points in the problem, docs/contacts.md "Speculative points"); contact_rest's
// certificate is offered on the touching points alone (where it holds, v = w = 0 keeps every
// speculative point within its constraint, carrying nothing). v and w (body frame) are updated
// in place; dx receives the deepest point's position correction (body frame). Returns the
// number of points that carry a normal impulse. At most kContactMaxPoints points. It loops and
// branches per point: one body at a time (a batched loop calls it per lane). With
// k.rolling_resistance > 0 each sweep gives each point, between its normal and its friction
// impulse, the rolling resistance's angular impulse (rolling_resistance_impulse, accumulated
// per point, capped by mu_r |r_i| J_n,i). With M (the 6x6 generalized mass, row-major; the inverse of Minv), a body
// lying on one plane is first offered contact_rest's certificate: when it holds, v = w = 0 at
// once and no sweep runs.
constexpr int kContactMaxPoints = 64;
// contact_resolve stops sweeping when a sweep changes no impulse by more than this fraction of
// the largest accumulated normal impulse. For a body lying on a surface that impulse is about
// its weight times the step (m g dt), so what is left unresolved changes a point's velocity by
// at most about 1e-6 g dt (2e-8 m/s at dt = 2 ms): a creep below 2e-7 m in 10 s, under the
// 1e-6 m the incline check allows; the next step's pass takes it up again. A tighter 1e-9 gives
// the same results to the validation's precision for 1.5 % more instructions per body-step on
// the wind scene (docs/contacts.md).
constexpr double kContactTolerance = 1e-6;
// contact_resolve's points lie on one plane (contact_rest) when their normals differ from the
// first's by less than this in 1 - cos (an angle below 1.4 mrad: the ground exactly, a flat roof
// or wall whose normals come from the wall distance's gradient)
constexpr double kContactPlaneCos = 1e-6;
template <typename T>
int contact_resolve(const ContactParams& k, const T* Minv, T* v, T* w, int count, const T* r,
                    const T* n, const T* depth, int passes, T* dx, const T* M = nullptr,
                    T horizon = T(0)) {
  const int m = count < kContactMaxPoints ? count : kContactMaxPoints;
  if (M && m >= 3 && !(k.rolling_resistance > T(0))) {
    // a body lying on one plane, its touching points (3 to kContactRestPoints) on it and
    // approaching slower than rest_speed: contact_rest's certificate, before the sweeps' set-up.
    // Speculative points (depth < 0) stay out of it: where it holds, v = w = 0 leaves each of
    // them where it is, within its constraint (it may approach at -depth / horizon), and it
    // carries nothing -- the exact solution of the problem with them too.
    T rt[3 * kContactRestPoints], nt[3 * kContactRestPoints];
    int mt = 0;
    bool plane = true;
    for (int i = 0; i < m && plane; ++i) {
      if (depth[i] < T(0)) continue;
      const T* ri = r + 3 * i;
      T wxr[3], vc[3];
      cross3(w, ri, wxr);
      for (int a = 0; a < 3; ++a) vc[a] = v[a] + wxr[a];
      const T* n0 = mt > 0 ? nt : n + 3 * i;
      plane = mt < kContactRestPoints && depth[i] >= T(0) &&
              dot3(n + 3 * i, n0) >= T(1) - T(kContactPlaneCos) &&
              dot3(vc, n + 3 * i) >= -T(k.rest_speed);
      if (!plane) break;
      for (int a = 0; a < 3; ++a) rt[3 * mt + a] = ri[a], nt[3 * mt + a] = n[3 * i + a];
      ++mt;
    }
    if (plane && mt >= 3) {
      const int carrying = contact_rest(k, M, v, w, mt, rt, nt);
      if (carrying > 0) {
        int deepest = 0;
        for (int i = 1; i < m; ++i)
          if (depth[i] > depth[deepest]) deepest = i;
        for (int a = 0; a < 3; ++a) dx[a] = depth[deepest] * n[3 * deepest + a];
        return carrying;
      }
    }
  }
  const T mu = T(k.friction), mur = T(k.rolling_resistance);
  const bool rolls = mur > T(0);
  const bool diagonal = inverse_mass_is_diagonal(Minv);
  T target[kContactMaxPoints], K[kContactMaxPoints][9], Kn[kContactMaxPoints][3],
      Jn[kContactMaxPoints],
      Jt[kContactMaxPoints][3], inv_knn[kContactMaxPoints], Lr[kContactMaxPoints][3],
      rlen[kContactMaxPoints];
  T best = T(0);
  dx[0] = dx[1] = dx[2] = T(0);
  for (int i = 0; i < m; ++i) {
    const T* ri = r + 3 * i;
    T wxr[3], vc[3];
    cross3(w, ri, wxr);
    for (int a = 0; a < 3; ++a) vc[a] = v[a] + wxr[a];
    const T vn = dot3(vc, n + 3 * i);
    target[i] = vn < -T(k.rest_speed) ? -T(k.restitution) * vn : T(0);
    // a speculative point (off the surface by -depth): it may approach until it closes the gap
    // in the next step, no faster
    if (depth[i] < T(0)) target[i] = horizon > T(0) ? depth[i] / horizon : T(0);
    // K of the point: its velocity change per unit impulse (symmetric positive definite)
    T dvc[3], dv[3], dw[3];
    for (int j = 0; j < 3; ++j) {
      const T ej[3] = {T(j == 0), T(j == 1), T(j == 2)};
      contact_response(Minv, ri, ej, dvc, dv, dw, diagonal);
      K[i][j] = dvc[0], K[i][3 + j] = dvc[1], K[i][6 + j] = dvc[2];
    }
    mul(K[i], n + 3 * i, Kn[i]);
    inv_knn[i] = T(1) / dot3(n + 3 * i, Kn[i]);
    Jn[i] = T(0);
    Jt[i][0] = Jt[i][1] = Jt[i][2] = T(0);
    Lr[i][0] = Lr[i][1] = Lr[i][2] = T(0);
    rlen[i] = std::sqrt(dot3(ri, ri));
    if (depth[i] > best) {
      best = depth[i];
      for (int a = 0; a < 3; ++a) dx[a] = depth[i] * n[3 * i + a];
    }
  }
  auto apply = [&](const T* ri, const T* J) {
    T dvc[3], dv[3], dw[3];
    contact_response(Minv, ri, J, dvc, dv, dw, diagonal);
    for (int a = 0; a < 3; ++a) v[a] += dv[a], w[a] += dw[a];
  };
  auto point_velocity = [&](const T* ri, T* vc) {
    T wxr[3];
    cross3(w, ri, wxr);
    for (int a = 0; a < 3; ++a) vc[a] = v[a] + wxr[a];
  };
  // the rolling resistance's angular impulse at point i (its accumulated impulse Lr[i] kept
  // within mu_r |r_i| Jn); returns its change as an impulse at the point's distance, N s
  auto roll = [&](int i, T jn) {
    T dL[3], dv[3], dw[3];
    rolling_resistance_impulse(Minv, w, mur * rlen[i] * jn, Lr[i], dL);
    torque_response(Minv, dL, dv, dw, diagonal);
    for (int a = 0; a < 3; ++a) v[a] += dv[a], w[a] += dw[a];
    return rlen[i] > T(0) ? std::sqrt(dot3(dL, dL)) / rlen[i] : T(0);
  };
  if (M && m == 1 && rolls && depth[0] >= T(0)) {
    // one point with rolling resistance, approaching slower than rest_speed: the impulse that
    // stops the body, [P; L] = -M [v; w], is one the point and the resistance can give when P
    // presses, lies in the friction cone, and leaves to the resistance a moment L - r x P of at
    // most mu_r |r| P_n (contact_rest's certificate for one point): then v = w = 0 at once
    T vc[3];
    point_velocity(r, vc);
    if (dot3(vc, n) >= -T(k.rest_speed)) {
      T P[3], L[3];
      stopping_impulse(M, v, w, P, L);
      const T pn = dot3(P, n);
      T Pt[3], rxP[3], Lroll[3];
      for (int a = 0; a < 3; ++a) Pt[a] = P[a] - pn * n[a];
      cross3(r, P, rxP);
      for (int a = 0; a < 3; ++a) Lroll[a] = L[a] - rxP[a];
      if (pn > T(0) && std::sqrt(dot3(Pt, Pt)) <= mu * pn &&
          std::sqrt(dot3(Lroll, Lroll)) <= mur * rlen[0] * pn) {
        for (int a = 0; a < 3; ++a) v[a] = T(0), w[a] = T(0);
        return 1;
      }
    }
  }
  if (m == 1 && depth[0] >= T(0)) {
    // one point (a sphere or an ellipsoid, a box on a corner): the impulse that stops it
    // (normal velocity to its target, no slip), K J = target n - v_c, is where the sweeps below
    // converge when it pulls not and lies in the friction cone (a body resting or rolling on
    // one point): taken at once, exactly; otherwise the sweeps find the sliding impulse
    T vc[3], want[3], J[3];
    point_velocity(r, vc);
    for (int a = 0; a < 3; ++a) want[a] = target[0] * n[a] - vc[a];
    solve3(K[0], want, J);
    const T jn = dot3(J, n);
    T jt[3];
    for (int a = 0; a < 3; ++a) jt[a] = J[a] - jn * n[a];
    if (jn >= T(0) && std::sqrt(dot3(jt, jt)) <= mu * jn) {
      if (!rolls) {
        apply(r, J);
        return jn > T(0) ? 1 : 0;
      }
      // with rolling resistance: that impulse, the rolling resistance's angular impulse (capped
      // by mu_r |r| jn), then the impulse that stops the point again; the sweeps below when
      // the sum leaves the friction cone
      const T v0[3] = {v[0], v[1], v[2]}, w0[3] = {w[0], w[1], w[2]};
      apply(r, J);
      roll(0, jn);
      T J2[3];
      point_velocity(r, vc);
      for (int a = 0; a < 3; ++a) want[a] = target[0] * n[a] - vc[a];
      solve3(K[0], want, J2);
      for (int a = 0; a < 3; ++a) J2[a] += J[a];
      const T jn2 = dot3(J2, n);
      for (int a = 0; a < 3; ++a) jt[a] = J2[a] - jn2 * n[a];
      if (jn2 >= T(0) && std::sqrt(dot3(jt, jt)) <= mu * jn2) {
        for (int a = 0; a < 3; ++a) J2[a] -= J[a];
        apply(r, J2);
        return jn2 > T(0) ? 1 : 0;
      }
      for (int a = 0; a < 3; ++a) v[a] = v0[a], w[a] = w0[a];
      Lr[0][0] = Lr[0][1] = Lr[0][2] = T(0);
    }
  }
  for (int p = 0; p < passes; ++p) {
    // the sweep's largest impulse change against the largest accumulated impulse: converged
    // when it is below kContactTolerance of it (a resting body: after 2 or 3 sweeps)
    T change = T(0), scale = T(0);
    for (int i = 0; i < m; ++i) {
      if (!(depth[i] >= T(0)) && !(depth[i] < T(0) && horizon > T(0))) continue;
      const T* ri = r + 3 * i;
      const T* ni = n + 3 * i;
      change = std::max(
          change, contact_point_sweep(
                      K[i], Kn[i], ni, target[i], inv_knn[i], mu, rolls, &Jn[i], Jt[i], &scale,
                      [&](T* vc) { point_velocity(ri, vc); },
                      [&](T dj) {
                        const T J[3] = {dj * ni[0], dj * ni[1], dj * ni[2]};
                        apply(ri, J);
                      },
                      [&](const T* J) { apply(ri, J); }, [&](T jn) { return roll(i, jn); }));
    }
    if (change <= T(kContactTolerance) * scale) break;
  }
  int carrying = 0;
  for (int i = 0; i < m; ++i) carrying += Jn[i] > T(0);
  return carrying;
}

}  // namespace lrigid
