#include "contact/island.h"

#include <algorithm>
#include <cmath>

#include "contact/bodies.h"
#include "contact/solver.h"

namespace lrigid {

void world_inverse_mass(const Mat6& Minv_body, const Mat3& R, double* W) {
  // block by block: R M_ij R^T (blockdiag(R, R) has no other blocks)
  Mat6 Ww;
  for (int bi = 0; bi < 2; ++bi)
    for (int bj = 0; bj < 2; ++bj)
      Ww.block<3, 3>(3 * bi, 3 * bj) =
          R * Minv_body.block<3, 3>(3 * bi, 3 * bj) * R.transpose();
  for (int i = 0; i < 6; ++i)
    for (int j = 0; j < 6; ++j) W[6 * i + j] = 0.5 * (Ww(i, j) + Ww(j, i));
}

namespace {

// What of a penetration the position correction removes in one step (island_resolve's moves):
// on the pile of 10 000 boxes the deepest overlap at 1 s is 0.32 mm with a half, 0.57 mm with all
// (the bodies pushed out at once overshoot into their neighbours and fall back)
constexpr double kPositionFraction = 0.5;

void body_point_velocity(const double* v, const double* w, const double* r, double* vc) {
  double wxr[3];
  cross3(w, r, wxr);
  for (int a = 0; a < 3; ++a) vc[a] = v[a] + wxr[a];
}

}  // namespace

void island_point_velocity(const IslandBody* bodies, const IslandPoint& p, double* vc) {
  body_point_velocity(bodies[p.a].v, bodies[p.a].w, p.ra, vc);
  if (p.b >= 0) {
    double vb[3];
    body_point_velocity(bodies[p.b].v, bodies[p.b].w, p.rb, vb);
    for (int a = 0; a < 3; ++a) vc[a] -= vb[a];
  }
}

int island_resolve(IslandBody* bodies, IslandPoint* pts, int count, int passes, double horizon,
                   double cw, double* moves, int passes_moving) {
  // What a sweep needs of a point, computed once, packed together: each body's velocity change
  // [dv; dw] per unit impulse along the world axes at the point (G = W [I; [r]x], 6 x 3,
  // row-major) and along the normal (G n), so that an impulse costs a 6 x 3 product per body (a
  // normal one a 6-vector) instead of contact_response's cross products and 6 x 6 product; the
  // point's K = the point rows of G_a + G_b, K n, 1 / n.K n, its target and impulses.
  struct Row {
    double Ga[18], Gb[18], Gan[6], Gbn[6];
    double K[9], Kn[3];
    double n[3], ra[3], rb[3];
    double inv_knn, target, mu;
    double jn, jt[3];
    int a, b;
    bool rolls;
  };
  // (kept from call to call, per thread: an island of a thousand bodies needs megabytes, which
  // allocated afresh would be page faults every step)
  thread_local std::vector<Row> rows;
  thread_local std::vector<int> live;  // the points the sweeps take, in order
  thread_local std::vector<double> xi, roll_L;
  // (grown only: every field a point's sweep reads is set below, and a vector of rows resized up
  // again would value-initialize them all, megabytes each step)
  if (rows.size() < size_t(count)) rows.resize(size_t(count));
  live.clear();
  // the bodies' velocities [v; w], packed for the sweeps
  int nb = 0;
  for (int i = 0; i < count; ++i) nb = std::max({nb, pts[i].a + 1, pts[i].b + 1});
  if (xi.size() < 6 * size_t(nb)) xi.resize(6 * size_t(nb));
  for (int m = 0; m < nb; ++m)
    for (int a = 0; a < 3; ++a) xi[6 * m + a] = bodies[m].v[a], xi[6 * m + 3 + a] = bodies[m].w[a];
  bool rolling = false;
  for (int i = 0; i < count && !rolling; ++i) rolling = pts[i].rolling > 0;
  if (rolling) roll_L.assign(3 * size_t(count), 0.0);
  // the impulses' scale is at least the impulse that changes a point's velocity by its resting
  // speed: an island whose points carry next to nothing (bodies parting, speculative points just
  // within the margin) is converged once no impulse changes by more than the tolerance of that,
  // where the largest impulse (1e-30 N s) would ask for round-off
  double floor = HUGE_VAL;
  bool moving = false;
  auto vel = [&](const Row& k, double* vc) {
    const double* xa = &xi[6 * size_t(k.a)];
    body_point_velocity(xa, xa + 3, k.ra, vc);
    if (k.b >= 0) {
      const double* xb = &xi[6 * size_t(k.b)];
      double vb[3];
      body_point_velocity(xb, xb + 3, k.rb, vb);
      for (int a = 0; a < 3; ++a) vc[a] -= vb[a];
    }
  };
  auto apply = [&](const Row& k, const double* J) {
    double* xa = &xi[6 * size_t(k.a)];
    for (int i = 0; i < 6; ++i)
      xa[i] += k.Ga[3 * i] * J[0] + k.Ga[3 * i + 1] * J[1] + k.Ga[3 * i + 2] * J[2];
    if (k.b >= 0) {
      double* xb = &xi[6 * size_t(k.b)];
      for (int i = 0; i < 6; ++i)
        xb[i] -= k.Gb[3 * i] * J[0] + k.Gb[3 * i + 1] * J[1] + k.Gb[3 * i + 2] * J[2];
    }
  };
  auto apply_n = [&](const Row& k, double dj) {
    double* xa = &xi[6 * size_t(k.a)];
    for (int i = 0; i < 6; ++i) xa[i] += k.Gan[i] * dj;
    if (k.b >= 0) {
      double* xb = &xi[6 * size_t(k.b)];
      for (int i = 0; i < 6; ++i) xb[i] -= k.Gbn[i] * dj;
    }
  };
  for (int i = 0; i < count; ++i) {
    const IslandPoint& p = pts[i];
    Row& k = rows[i];
    k.a = p.a, k.b = p.b;
    for (int e = 0; e < 3; ++e) k.n[e] = p.n[e], k.ra[e] = p.ra[e], k.rb[e] = p.rb[e];
    // G of each body and K: the relative velocity change of the point per unit impulse (a gets
    // J, b gets -J)
    for (int j = 0; j < 3; ++j) {
      const double ej[3] = {double(j == 0), double(j == 1), double(j == 2)};
      double ca[3], cb[3] = {0, 0, 0}, dv[3], dw[3];
      contact_response(bodies[p.a].W, p.ra, ej, ca, dv, dw);
      for (int a = 0; a < 3; ++a) k.Ga[3 * a + j] = dv[a], k.Ga[3 * (3 + a) + j] = dw[a];
      if (p.b >= 0) {
        contact_response(bodies[p.b].W, p.rb, ej, cb, dv, dw);
        for (int a = 0; a < 3; ++a) k.Gb[3 * a + j] = dv[a], k.Gb[3 * (3 + a) + j] = dw[a];
      }
      for (int a = 0; a < 3; ++a) k.K[3 * a + j] = ca[a] + cb[a];
    }
    for (int a = 0; a < 6; ++a) {
      k.Gan[a] = k.Ga[3 * a] * p.n[0] + k.Ga[3 * a + 1] * p.n[1] + k.Ga[3 * a + 2] * p.n[2];
      k.Gbn[a] = p.b >= 0 ? k.Gb[3 * a] * p.n[0] + k.Gb[3 * a + 1] * p.n[1] +
                                k.Gb[3 * a + 2] * p.n[2]
                          : 0.0;
    }
    mul(k.K, p.n, k.Kn);
    k.inv_knn = 1.0 / dot3(p.n, k.Kn);
    k.mu = p.friction;
    k.rolls = p.rolling > 0;
    double vc[3];
    vel(k, vc);
    const double vn = dot3(vc, p.n);
    k.target = vn < -p.rest_speed ? -p.restitution * vn : 0.0;
    // (a point moving faster than the resting speed, touching or speculative: the island is in
    // motion)
    if ((p.depth >= 0 || horizon > 0) && !(dot3(vc, vc) <= p.rest_speed * p.rest_speed))
      moving = true;
    // a speculative point: it may approach as fast as closes its gap in the next step, no
    // faster; one approaching faster than the resting speed that would close it within the step
    // is an impact, taken now with its restitution (up to one step's travel early)
    if (p.depth < 0 && !(vn < -p.rest_speed && -vn * horizon > -p.depth))
      k.target = horizon > 0 ? p.depth / horizon : 0.0;
    const bool solved = p.depth >= 0 || (p.depth < 0 && horizon > 0);
    if (solved) {
      live.push_back(i);
      floor = std::min(floor, p.rest_speed * k.inv_knn);
    }
    // the warm start's impulses, within the constraints (pushing only, inside the friction cone)
    k.jn = solved && p.jn > 0 ? p.jn : 0.0;  // (and not NaN)
    const double along = dot3(p.jt, p.n);
    for (int a = 0; a < 3; ++a) k.jt[a] = p.jt[a] - along * p.n[a];
    const double norm = std::sqrt(dot3(k.jt, k.jt)), cap = k.mu * k.jn;
    const double clip = !(norm < HUGE_VAL) ? 0.0 : norm > cap ? cap / norm : 1.0;
    for (int a = 0; a < 3; ++a) k.jt[a] *= clip;
  }
  // the warm start, once every target is set from the velocities before it
  for (const int i : live) {
    const Row& k = rows[i];
    if (!(k.jn > 0)) continue;
    double J[3];
    for (int a = 0; a < 3; ++a) J[a] = k.jn * k.n[a] + k.jt[a];
    apply(k, J);
  }
  const int nlive = int(live.size());
  if (moving && passes_moving >= 0) passes = std::min(passes, passes_moving);
  for (int pass = 0; pass < passes; ++pass) {
    double change = 0, scale = 0;
    for (int ii = 0; ii < nlive; ++ii) {
      const int i = live[size_t(ii)];
      Row& k = rows[i];
      // the rolling resistance against the rotation of a relative to b
      auto roll = [&](double jn) {
        const IslandPoint& p = pts[i];
        double* xa = &xi[6 * size_t(k.a)];
        double* xb = k.b >= 0 ? &xi[6 * size_t(k.b)] : nullptr;
        double wr[3], Wsum[36];
        for (int a = 0; a < 3; ++a) wr[a] = xa[3 + a] - (xb ? xb[3 + a] : 0.0);
        for (int a = 0; a < 36; ++a) Wsum[a] = bodies[k.a].W[a] + (xb ? bodies[k.b].W[a] : 0.0);
        const double rlen = std::sqrt(dot3(k.ra, k.ra));
        double dL[3], dv[3], dw[3];
        rolling_resistance_impulse(Wsum, wr, p.rolling * rlen * jn, &roll_L[3 * size_t(i)], dL);
        torque_response(bodies[k.a].W, dL, dv, dw);
        for (int a = 0; a < 3; ++a) xa[a] += dv[a], xa[3 + a] += dw[a];
        if (xb) {
          const double mL[3] = {-dL[0], -dL[1], -dL[2]};
          torque_response(bodies[k.b].W, mL, dv, dw);
          for (int a = 0; a < 3; ++a) xb[a] += dv[a], xb[3 + a] += dw[a];
        }
        return rlen > 0 ? std::sqrt(dot3(dL, dL)) / rlen : 0.0;
      };
      change = std::max(
          change, contact_point_sweep(
                      k.K, k.Kn, k.n, k.target, k.inv_knn, k.mu, k.rolls, &k.jn, k.jt, &scale,
                      [&](double* vc) { vel(k, vc); }, [&](double dj) { apply_n(k, dj); },
                      [&](const double* J) { apply(k, J); }, roll));
    }
    if (change <= kContactTolerance * std::max(scale, floor)) break;
  }
  if (moves) {
    // the positions: what remains of each penetration once the step's update has taken cw times
    // the velocity change (a fraction kPositionFraction of it), removed by Gauss-Seidel sweeps on
    // the bodies' displacements, each body moved as a particle of its translational inverse mass
    // W_vv (a unit "position impulse" along n moves a by W_vv,a n and b by -W_vv,b n), each
    // point's accumulated correction pushing only
    struct Deep {
      int a, b;
      double n[3], ua[3], ub[3];
      double left, inv, lam;
    };
    thread_local std::vector<Deep> deep;
    deep.clear();
    std::fill(moves, moves + 3 * size_t(nb), 0.0);  // (the sweeps below accumulate into it)
    double pfloor = HUGE_VAL;
    for (const int i : live) {
      const IslandPoint& p = pts[i];
      if (!(p.depth > 0)) continue;
      double vc1[3], vc0[3];
      vel(rows[i], vc1);
      island_point_velocity(bodies, p, vc0);  // (bodies: still the velocities before)
      const double l = p.depth - p.slop - cw * (dot3(vc1, p.n) - dot3(vc0, p.n));
      if (!(l > 0)) continue;
      Deep d;
      d.a = p.a, d.b = p.b;
      for (int e = 0; e < 3; ++e) d.n[e] = p.n[e];
      auto linear = [&](const double* W, double* u) {
        for (int r = 0; r < 3; ++r)
          u[r] = W[6 * r] * p.n[0] + W[6 * r + 1] * p.n[1] + W[6 * r + 2] * p.n[2];
      };
      linear(bodies[p.a].W, d.ua);
      if (p.b >= 0) linear(bodies[p.b].W, d.ub);
      else d.ub[0] = d.ub[1] = d.ub[2] = 0;
      const double k = dot3(p.n, d.ua) + dot3(p.n, d.ub);
      if (!(k > 0)) continue;
      d.inv = 1 / k;
      d.left = kPositionFraction * l;
      pfloor = std::min(pfloor, kPairSkin * d.inv);
      d.lam = 0;
      deep.push_back(d);
    }
    // (converged as the impulses, with a floor: the correction that moves a point by the skin)
    for (int pass = 0; pass < passes && !deep.empty(); ++pass) {
      double change = 0, scale = 0;
      for (Deep& d : deep) {
        double* xa = &moves[3 * size_t(d.a)];
        double* xb = d.b >= 0 ? &moves[3 * size_t(d.b)] : nullptr;
        double gap = dot3(xa, d.n);
        if (xb) gap -= dot3(xb, d.n);
        const double l_new = std::max(0.0, d.lam + (d.left - gap) * d.inv);
        const double dl = l_new - d.lam;
        d.lam = l_new;
        for (int e = 0; e < 3; ++e) xa[e] += d.ua[e] * dl;
        if (xb)
          for (int e = 0; e < 3; ++e) xb[e] -= d.ub[e] * dl;
        change = std::max(change, std::abs(dl));
        scale = std::max(scale, l_new);
      }
      if (change <= kContactTolerance * std::max(scale, pfloor)) break;
    }
  }
  for (int m = 0; m < nb; ++m)
    for (int a = 0; a < 3; ++a) bodies[m].v[a] = xi[6 * m + a], bodies[m].w[a] = xi[6 * m + 3 + a];
  int carrying = 0;
  for (int i = 0; i < count; ++i) {
    IslandPoint& p = pts[i];
    p.jn = rows[i].jn;
    for (int a = 0; a < 3; ++a) p.jt[a] = rows[i].jt[a];
    carrying += p.jn > 0;
  }
  return carrying;
}

}  // namespace lrigid
