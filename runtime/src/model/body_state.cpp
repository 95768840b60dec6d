#include "model/body_state.h"

#include "util/fast_math.h"
#include "util/lane.h"

namespace lrigid {

BodyState load_body(State& st, size_t i) {
  return BodyState{st.x[i], st.q[i], st.v[i], st.w[i], st.u_seen[i], st.history_of(i)};
}

void store_body(const BodyState& b, size_t i, State* st) {
  st->x[i] = b.x;
  st->q[i] = b.q;
  st->v[i] = b.v;
  st->w[i] = b.w;
  st->u_seen[i] = b.u_seen;
}

Quat rotate_body(const Quat& q, const Vec3& theta) {
  const double q0[4] = {q.w(), q.x(), q.y(), q.z()};
  double qn[4];
  exp_rotate<ScalarMath>(q0, theta.data(), qn);
  return Quat(qn[0], qn[1], qn[2], qn[3]);
}

}  // namespace lrigid
