#include "model/state.h"

namespace lrigid {

const char* body_status_name(BodyStatus s) {
  switch (s) {
    case BodyStatus::Moving: return "moving";
    case BodyStatus::Landed: return "landed";
    case BodyStatus::Exited: return "exited";
    case BodyStatus::Failed: return "failed";
  }
  return "?";
}

}  // namespace lrigid
