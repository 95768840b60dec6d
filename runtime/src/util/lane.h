// What the physics kernels are written with: plain numbers of type T (double on the scalar
// step, double or float in the batched steps' loops across bodies), 3-vectors as T[3], no
// branches that a loop across lanes could not turn into selects. Every kernel is inlined into
// its caller (LRIGID_LANE): into each multiversioned loop of the batched steps (a call would run
// the baseline version) and into the scalar step's Eigen wrappers in effects/.
#pragma once
#include <cmath>

namespace lrigid {

#define LRIGID_LANE inline __attribute__((always_inline))

template <typename T>
LRIGID_LANE T dot3(const T* a, const T* b) {
  return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}

// c = a x b
template <typename T>
LRIGID_LANE void cross3(const T* a, const T* b, T* c) {
  c[0] = a[1] * b[2] - a[2] * b[1];
  c[1] = a[2] * b[0] - a[0] * b[2];
  c[2] = a[0] * b[1] - a[1] * b[0];
}

// R (row major) of the unit quaternion q = (w, x, y, z), as Eigen's toRotationMatrix
template <typename T>
LRIGID_LANE void rotation(const T* q, T* R) {
  const T w = q[0], x = q[1], y = q[2], z = q[3];
  const T tx = T(2) * x, ty = T(2) * y, tz = T(2) * z;
  const T twx = tx * w, twy = ty * w, twz = tz * w, txx = tx * x, txy = ty * x, txz = tz * x;
  const T tyy = ty * y, tyz = tz * y, tzz = tz * z;
  R[0] = T(1) - (tyy + tzz), R[1] = txy - twz, R[2] = txz + twy;
  R[3] = txy + twz, R[4] = T(1) - (txx + tzz), R[5] = tyz - twx;
  R[6] = txz - twy, R[7] = tyz + twx, R[8] = T(1) - (txx + tyy);
}

// b = R a
template <typename T>
LRIGID_LANE void mul(const T* R, const T* a, T* b) {
#pragma GCC unroll 3
  for (int i = 0; i < 3; ++i) b[i] = R[3 * i] * a[0] + R[3 * i + 1] * a[1] + R[3 * i + 2] * a[2];
}

// b = R^T a
template <typename T>
LRIGID_LANE void mul_t(const T* R, const T* a, T* b) {
#pragma GCC unroll 3
  for (int i = 0; i < 3; ++i) b[i] = R[i] * a[0] + R[3 + i] * a[1] + R[6 + i] * a[2];
}

// b = q a q^-1: the vector a (body frame) in the world frame, q = (w, x, y, z) unit
template <typename T>
LRIGID_LANE void rotate_by(const T* q, const T* a, T* b) {
  const T t[3] = {T(2) * (q[2] * a[2] - q[3] * a[1]), T(2) * (q[3] * a[0] - q[1] * a[2]),
                  T(2) * (q[1] * a[1] - q[2] * a[0])};
  b[0] = a[0] + q[0] * t[0] + (q[2] * t[2] - q[3] * t[1]);
  b[1] = a[1] + q[0] * t[1] + (q[3] * t[0] - q[1] * t[2]);
  b[2] = a[2] + q[0] * t[2] + (q[1] * t[1] - q[2] * t[0]);
}

// qn = q cay(theta), theta = 2 a (rad, body frame): q times the quaternion (1, a), normalized
// (the rotation by the angle 2 atan(|a|)), q and qn as (w, x, y, z). The orientation update of
// every step (integrate/dynamics.cpp rotate_cayley and the batched loops).
template <typename T>
LRIGID_LANE void cayley_rotate(const T* q, const T* a, T* qn) {
  const T qw = q[0], qx = q[1], qy = q[2], qz = q[3];
  const T ax = a[0], ay = a[1], az = a[2];
  const T nw = qw - (qx * ax + qy * ay + qz * az);
  const T nx = qw * ax + qx + (qy * az - qz * ay);
  const T ny = qw * ay + qy + (qz * ax - qx * az);
  const T nz = qw * az + qz + (qx * ay - qy * ax);
  const T inv = T(1) / std::sqrt(nw * nw + nx * nx + ny * ny + nz * nz);
  qn[0] = nw * inv, qn[1] = nx * inv, qn[2] = ny * inv, qn[3] = nz * inv;
}

// qn = q exp(theta): q times the rotation by the body-frame rotation vector theta (rad), the
// quaternion (cos(|theta|/2), sin(|theta|/2) theta/|theta|), or (1, theta/2) below 1e-8 rad,
// normalized; q and qn as (w, x, y, z). The euler and rk4 steps' orientation update
// (integrators.cpp rotate_body and the batched loops). Math: util/fast_math.h (LaneMath in the
// batched loops).
template <class Math, typename T>
LRIGID_LANE void exp_rotate(const T* q, const T* theta, T* qn) {
  const T angle = std::sqrt(theta[0] * theta[0] + theta[1] * theta[1] + theta[2] * theta[2]);
  const bool small = angle < T(1e-8);
  double c, s;
  Math::sincos(0.5 * double(small ? T(1) : angle), &c, &s);
  const T dw = small ? T(1) : T(c);
  const T f = small ? T(0.5) : T(s) / angle;
  const T dx = f * theta[0], dy = f * theta[1], dz = f * theta[2];
  const T qw = q[0], qx = q[1], qy = q[2], qz = q[3];
  const T nw = qw * dw - (qx * dx + qy * dy + qz * dz);
  const T nx = qw * dx + dw * qx + (qy * dz - qz * dy);
  const T ny = qw * dy + dw * qy + (qz * dx - qx * dz);
  const T nz = qw * dz + dw * qz + (qx * dy - qy * dx);
  const T inv = T(1) / std::sqrt(nw * nw + nx * nx + ny * ny + nz * nz);
  qn[0] = nw * inv, qn[1] = nx * inv, qn[2] = ny * inv, qn[3] = nz * inv;
}

// d theta/dt = dexp^-1(theta) w for the body-frame chart q exp(theta), to O(|theta|^3):
// w + 1/2 theta x w + 1/12 theta x (theta x w) (the rk4 step on SO(3), integrators.h)
template <typename T>
LRIGID_LANE void dexpinv(const T* theta, const T* w, T* out) {
  T a[3], b[3];
  cross3(theta, w, a);
  cross3(theta, a, b);
#pragma GCC unroll 3
  for (int i = 0; i < 3; ++i) out[i] = w[i] + T(0.5) * a[i] + b[i] / T(12);
}

}  // namespace lrigid
