// The batched rigid-body step for a full M (meshes) in double precision: one of the six
// instantiations of rigid_batch_step.h, each in its own file so that they compile side by side.
#include "integrate/rigid_batch_step.h"

namespace lrigid::rigid_batch_detail {

BlockStats advance_full_double(const Model& model, const BodyType& type, State* state,
                               const uint32_t* body, int count, uint64_t first, uint64_t last,
                               StretchSweep* sweep) {
  return advance<double, FullMass>(model, type, state, body, count, first, last, sweep);
}

}  // namespace lrigid::rigid_batch_detail
