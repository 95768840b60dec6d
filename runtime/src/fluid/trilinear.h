// The trilinear record kernel, written once: the scalar step's FluidField::sample_frame
// (fluid/field.cpp, T = double) and the batched steps' sample_lanes (integrate/batch_lanes.h,
// double or float) both blend a cell's 8 corner records (GridRecord: 8 floats, one vector) with it.
// A corner's whole record is taken at once: across lanes the same sums would be 56 gathers per
// lane, which cost more than the arithmetic.
#pragma once
#include <cstring>

#include "util/lane.h"

namespace lrigid {

// 8 values of type T in one vector (GCC's and Clang's vector extension), a record's slots.
template <typename T>
struct Record8 {
  typedef T type __attribute__((vector_size(8 * sizeof(T))));
};

// The sums over the corners c = cx + 2 cy + 4 cz of the cell whose first record starts at r0
// (the corners' records at r0 + off[c], in floats), at fractions f (0..1 per axis) of the cell:
//   v  = sum_c valid_c w_c rec_c     (w_c the trilinear weights; slot 6 = the valid weight W,
//                                      since valid_c is 1 or 0),
//   dk = sum_c (dw_c / df_k) rec_c   (k = 0, 1, 2: per unit index; with Gradients only).
// Returns the number of valid corners. Gradients are meaningful only when all 8 are valid.
// Blend: the records of two frames of a time-dependent field, r0 (frame a) and r0b (frame b,
// the same cell), blended as rec_a + lam (rec_b - rec_a) before the sums (the sums are linear:
// the blend of the two frames' sums, for one pass over the corners), and in dv the sum
// sum_c valid_c w_c (rec_b - rec_a) (times 1 / (t_b - t_a): the rate of change in time). The
// frames share the valid points (the mesh does not move).
template <typename T, bool Gradients, bool Blend = false>
LRIGID_LANE int trilinear_record(const float* r0, const int* off, const T* f,
                                 typename Record8<T>::type* v, typename Record8<T>::type* d0,
                                 typename Record8<T>::type* d1, typename Record8<T>::type* d2,
                                 const float* r0b = nullptr, T lam = T(0),
                                 typename Record8<T>::type* dv = nullptr) {
  typedef typename Record8<T>::type V8;
  typedef float F8 __attribute__((vector_size(32)));
  const T gx[2] = {T(1) - f[0], f[0]}, gy[2] = {T(1) - f[1], f[1]}, gz[2] = {T(1) - f[2], f[2]};
  V8 sv = {}, s0 = {}, s1 = {}, s2 = {}, sd = {};
  int nvalid = 0;
#pragma GCC unroll 8
  for (int c = 0; c < 8; ++c) {
    const int cx = c & 1, cy = (c >> 1) & 1, cz = c >> 2;
    F8 gf;
    std::memcpy(&gf, r0 + off[c], sizeof gf);
    V8 g = __builtin_convertvector(gf, V8);
    const T valid = g[6];
    nvalid += valid != T(0);
    const T wv = valid * (gx[cx] * gy[cy] * gz[cz]);
    if constexpr (Blend) {
      F8 hf;
      std::memcpy(&hf, r0b + off[c], sizeof hf);
      const V8 diff = __builtin_convertvector(hf, V8) - g;
      sd += wv * diff;
      g += lam * diff;
    }
    sv += wv * g;
    if constexpr (Gradients) {
      s0 += ((cx ? T(1) : T(-1)) * gy[cy] * gz[cz]) * g;
      s1 += (gx[cx] * (cy ? T(1) : T(-1)) * gz[cz]) * g;
      s2 += (gx[cx] * gy[cy] * (cz ? T(1) : T(-1))) * g;
    }
  }
  *v = sv;
  *d0 = s0;
  *d1 = s1;
  *d2 = s2;
  if constexpr (Blend) *dv = sd;
  return nvalid;
}

// One float slot of the cell's 8 corner records (r0 + off[c] + slot, in floats), blended at
// fractions f (0..1 per axis), and its derivative per unit index along each axis (grad). The
// same sums as trilinear_record's for that slot without its valid weighting (every corner
// counts), as three nested linear blends: x first, then y, then z, and the derivatives from
// the same differences. The scalar field's wall distance (slot 7: FluidField::wall_distance and
// sample_frame): a contact queries it at each of a body's points near a wall, so it is the
// cheaper form of one slot.
template <typename T>
LRIGID_LANE T trilinear_slot(const float* r0, const int* off, int slot, const T* f, T* grad) {
  T c[8];
#pragma GCC unroll 8
  for (int k = 0; k < 8; ++k) c[k] = T(r0[off[k] + slot]);
  // along x: the four edges' values and differences (corners 2j and 2j + 1)
  T ex[4], dx[4];
#pragma GCC unroll 4
  for (int j = 0; j < 4; ++j) {
    dx[j] = c[2 * j + 1] - c[2 * j];
    ex[j] = c[2 * j] + f[0] * dx[j];
  }
  // along y: the two faces z = 0 and z = 1
  const T dy0 = ex[1] - ex[0], dy1 = ex[3] - ex[2];
  const T fy0 = ex[0] + f[1] * dy0, fy1 = ex[2] + f[1] * dy1;
  const T gx0 = dx[0] + f[1] * (dx[1] - dx[0]), gx1 = dx[2] + f[1] * (dx[3] - dx[2]);
  // along z
  const T dz = fy1 - fy0;
  grad[0] = gx0 + f[2] * (gx1 - gx0);
  grad[1] = dy0 + f[2] * (dy1 - dy0);
  grad[2] = dz;
  return fy0 + f[2] * dz;
}

}  // namespace lrigid
