// The end-of-step events of one body: where it first touches the ground inside a step (touchdown,
// and any surface: locate_event), a landing, and a body that stops (stop_body: landed, exited,
// failed). The rules the scalar loop (integrate/simulation.cpp) and the batched steps
// (integrate/batch_lanes.h) share.
#pragma once
#include <cmath>
#include <functional>
#include <string>

#include "model/body_state.h"
#include "model/model.h"

namespace lrigid {

// How far below its centre of mass the body reaches, m, with r the third row of its rotation
// matrix (the world z of each body axis), h its half extents about the volume centroid and c the
// centroid from the centre of mass (BodyType::r_cob, body frame; zero for a uniform body): exact
// for spheres and ellipsoids (round: the support function sqrt(sum (r_a h_a)^2)) and boxes
// (sum |r_a| h_a), less the centroid's height r . c; for a mesh, its bounding box's. Written once
// for the scalar and the batched steps (batch_lanes.h lane_landed).
template <typename T>
inline T ground_reach(bool round, const T* r, const T* h, const T* c) {
  const T a = r[0] * h[0], b = r[1] * h[1], d = r[2] * h[2];
  const T box = std::abs(a) + std::abs(b) + std::abs(d);
  const T ell = std::sqrt(a * a + b * b + d * d);
  return (round ? ell : box) - (r[0] * c[0] + r[1] * c[1] + r[2] * c[2]);
}
inline bool is_round(const BodyType& type) {
  return type.shape.type == ShapeType::Sphere || type.shape.type == ShapeType::Ellipsoid;
}

// the body's lowest point (ground_reach) is on or below the ground
bool touches_ground(const Model& m, const BodyType& type, const BodyState& s);

// Where within a step from `a` to `b` (model.dt apart, b touching the ground) the body first
// touches it (an event located inside the step): the first root of the lowest point's
// height above the ground along the step's motion, a cubic Hermite interpolant through both ends'
// positions and world velocities and through both ends' orientations and their rates (q' = q w/2,
// the quaternion normalised), third order like rk4's own dense output, so that a landing does not
// cap a scheme's order at 1. Returns the time from the start of the step, in [0, dt] (dt when a
// already touched: a body that starts on the ground lands at the end of its first step, as before);
// *at is the state there (velocities interpolated linearly; the history pointer is a's).
double locate_touchdown(const Model& m, const BodyType& type, const BodyState& a,
                        const BodyState& b, BodyState* at);

// The same root for any clearance: the first time within a step of duration h from a to b where
// gap(x, q) (m; > 0 apart, <= 0 touching; gap at a > 0) reaches 0 along that interpolant.
// Returns it from the start of the step, in (0, h]; *at as above. Used by locate_touchdown (the
// ground) and by the contact pass for an impact on the ground or a wall inside a step
// (integrate/impacts.h).
double locate_event(const Model& m, const BodyType& type, const BodyState& a, const BodyState& b,
                    double h, const std::function<double(const Vec3&, const Quat&)>& gap,
                    BodyState* at);

// A colliding ground's first touchdown (landings.csv: t_touch, x_touch of body i), which the
// contact pass recorded at the end of the step that began at t, moved to where it happened inside
// it: locate_touchdown from a (the step's start) to b (its end, before the contact).
void record_touchdown(const Model& m, const BodyType& type, size_t i, double t, const BodyState& a,
                      const BodyState& b, State* st);

// A step from b that left the fluid would take the body onto a colliding ground (its
// predicted position touches it): the caller tries speculative_ground_contact and the step again.
bool heads_into_ground(const Model& m, const BodyType& type, const BodyState& b);

// Stops body i after its step from t did not succeed (out: Exited or Failed; `failure`: why it
// failed), with b its state at the start of that step: a step that would take it onto the ground
// lands it where its predicted straight motion touches the ground (b moves there; the caller sets
// it at rest), otherwise it exited or failed at t, with the
// reason (for an exit: where one more step would have taken it). With "outside": "remove", a
// body that left the grid is hidden from then on (st->hidden). Writes st's status, t_stop,
// reason and hidden; returns the status.
BodyStatus stop_body(const Model& m, const BodyType& type, size_t i, double t, StepOutcome out,
                     const std::string& failure, BodyState* b, State* st);

}  // namespace lrigid
