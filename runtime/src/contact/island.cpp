#include "contact/island.h"

#include <algorithm>
#include <cmath>

#include "contact/solver.h"

namespace lrigid {

void world_inverse_mass(const Mat6& Minv_body, const Mat3& R, double* W) {
  Mat6 B = Mat6::Zero();
  B.topLeftCorner<3, 3>() = R;
  B.bottomRightCorner<3, 3>() = R;
  const Mat6 Ww = B * Minv_body * B.transpose();
  for (int i = 0; i < 6; ++i)
    for (int j = 0; j < 6; ++j) W[6 * i + j] = 0.5 * (Ww(i, j) + Ww(j, i));
}

namespace {

void body_point_velocity(const IslandBody& b, const double* r, double* vc) {
  double wxr[3];
  cross3(b.w, r, wxr);
  for (int a = 0; a < 3; ++a) vc[a] = b.v[a] + wxr[a];
}

// adds the velocity change of body b when the impulse s J acts at r
void push(IslandBody& b, const double* r, const double* J, double s) {
  const double Js[3] = {s * J[0], s * J[1], s * J[2]};
  double dvc[3], dv[3], dw[3];
  contact_response(b.W, r, Js, dvc, dv, dw);
  for (int a = 0; a < 3; ++a) b.v[a] += dv[a], b.w[a] += dw[a];
}

}  // namespace

void island_point_velocity(const IslandBody* bodies, const IslandPoint& p, double* vc) {
  body_point_velocity(bodies[p.a], p.ra, vc);
  if (p.b >= 0) {
    double vb[3];
    body_point_velocity(bodies[p.b], p.rb, vb);
    for (int a = 0; a < 3; ++a) vc[a] -= vb[a];
  }
}

int island_resolve(IslandBody* bodies, IslandPoint* pts, int count, int passes, double horizon) {
  struct Work {
    double K[9];
    double inv_knn;
    double target;
    double Wsum[36];  // angular block used by the rolling resistance
    double L[3];
    double rlen;
  };
  std::vector<Work> work(static_cast<size_t>(count));
  for (int i = 0; i < count; ++i) {
    IslandPoint& p = pts[i];
    Work& k = work[i];
    // K: the relative velocity change of the point per unit impulse (a gets J, b gets -J)
    for (int j = 0; j < 3; ++j) {
      const double ej[3] = {double(j == 0), double(j == 1), double(j == 2)};
      double ca[3], cb[3] = {0, 0, 0}, dv[3], dw[3];
      contact_response(bodies[p.a].W, p.ra, ej, ca, dv, dw);
      if (p.b >= 0) contact_response(bodies[p.b].W, p.rb, ej, cb, dv, dw);
      for (int a = 0; a < 3; ++a) k.K[3 * a + j] = ca[a] + cb[a];
    }
    double Kn[3];
    mul(k.K, p.n, Kn);
    k.inv_knn = 1.0 / dot3(p.n, Kn);
    double vc[3];
    island_point_velocity(bodies, p, vc);
    const double vn = dot3(vc, p.n);
    k.target = vn < -p.rest_speed ? -p.restitution * vn : 0.0;
    // a speculative point: it may approach as fast as closes its gap in the next step, no
    // faster; one approaching faster than the resting speed that would close it within the step
    // is an impact, taken now with its restitution (up to one step's travel early)
    if (p.depth < 0 && !(vn < -p.rest_speed && -vn * horizon > -p.depth))
      k.target = horizon > 0 ? p.depth / horizon : 0.0;
    for (int a = 0; a < 36; ++a)
      k.Wsum[a] = bodies[p.a].W[a] + (p.b >= 0 ? bodies[p.b].W[a] : 0.0);
    k.L[0] = k.L[1] = k.L[2] = 0;
    const double* r = p.ra;
    k.rlen = std::sqrt(dot3(r, r));
    p.jn = 0;
    p.jt[0] = p.jt[1] = p.jt[2] = 0;
  }
  for (int pass = 0; pass < passes; ++pass) {
    double change = 0, scale = 0;
    for (int i = 0; i < count; ++i) {
      IslandPoint& p = pts[i];
      Work& k = work[i];
      if (!(p.depth >= 0) && !(p.depth < 0 && horizon > 0)) continue;
      IslandBody& A = bodies[p.a];
      auto vel = [&](double* vc) { island_point_velocity(bodies, p, vc); };
      auto apply = [&](const double* J) {
        push(A, p.ra, J, 1.0);
        if (p.b >= 0) push(bodies[p.b], p.rb, J, -1.0);
      };
      // the rolling resistance against the rotation of a relative to b
      auto roll = [&](double jn) {
        if (!(p.rolling > 0)) return 0.0;
        double wr[3];
        for (int a = 0; a < 3; ++a) wr[a] = A.w[a] - (p.b >= 0 ? bodies[p.b].w[a] : 0.0);
        double dL[3], dv[3], dw[3];
        rolling_resistance_impulse(k.Wsum, wr, p.rolling * k.rlen * jn, k.L, dL);
        torque_response(A.W, dL, dv, dw);
        for (int a = 0; a < 3; ++a) A.v[a] += dv[a], A.w[a] += dw[a];
        if (p.b >= 0) {
          IslandBody& B = bodies[p.b];
          const double mL[3] = {-dL[0], -dL[1], -dL[2]};
          torque_response(B.W, mL, dv, dw);
          for (int a = 0; a < 3; ++a) B.v[a] += dv[a], B.w[a] += dw[a];
        }
        return k.rlen > 0 ? std::sqrt(dot3(dL, dL)) / k.rlen : 0.0;
      };
      change = std::max(change, contact_point_sweep(k.K, p.n, k.target, k.inv_knn, p.friction,
                                                    &p.jn, p.jt, &scale, vel, apply, roll));
    }
    if (change <= kContactTolerance * scale) break;
  }
  int carrying = 0;
  for (int i = 0; i < count; ++i) carrying += pts[i].jn > 0;
  return carrying;
}

}  // namespace lrigid
