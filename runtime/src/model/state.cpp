#include "model/state.h"

namespace lrigid {

const char* body_status_name(BodyStatus s) {
  switch (s) {
    case BodyStatus::Moving: return "moving";
    case BodyStatus::Landed: return "landed";
    case BodyStatus::Exited: return "exited";
    case BodyStatus::Failed: return "failed";
    case BodyStatus::Sleeping: return "sleeping";
    case BodyStatus::Unreleased: return "unreleased";
  }
  return "?";
}

uint8_t State::state_code(size_t i) const {
  switch (status[i]) {
    case BodyStatus::Moving: return i < contact.size() ? uint8_t(contact[i]) : 0;
    case BodyStatus::Sleeping: return 3;
    case BodyStatus::Exited: return 4;
    case BodyStatus::Landed: return 5;
    case BodyStatus::Failed: return 6;
    case BodyStatus::Unreleased: return 7;
  }
  return 0;
}

const char* const kStateNames[kStateCount] = {"flying", "sliding", "resting", "sleeping",
                                              "exited", "landed",  "failed",  "unreleased"};

const char* State::state_name(size_t i) const { return kStateNames[state_code(i)]; }

int state_code_from_name(const std::string& name) {
  for (int c = 0; c < kStateCount; ++c)
    if (name == kStateNames[c]) return c;
  return -1;
}

}  // namespace lrigid
