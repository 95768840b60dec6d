#include "integrate/step_end.h"

#include <cmath>

#include "contact/events.h"
#include "contact/pass.h"
#include "contact/sleep.h"
#include "integrate/impacts.h"
#include "integrate/integrators.h"

namespace lrigid {

StepOutcome retry_into_ground(const Model& model, const BodyType& type, size_t i, uint64_t k,
                              double t, BodyState* b, BodyState* start, std::string* reason,
                              State* st, bool* floor_impact, bool* retaken) {
  *floor_impact = false;
  *retaken = false;
  if (!heads_into_ground(model, type, *b)) return StepOutcome::Exited;
  if (impact_through_floor(model, type, i, t, b, st)) {
    *floor_impact = true;
    *retaken = true;
    return StepOutcome::Ok;
  }
  if (!speculative_ground_contact(model, type, b)) return StepOutcome::Exited;
  *retaken = true;
  *start = *b;
  return step_body(model, type, static_cast<uint32_t>(i), k, t, b, reason);
}

StepEnd finish_step(const Model& model, const BodyType& type, size_t i, double t, uint64_t last,
                    StepOutcome out, const std::string& reason, bool near, const bool* landed,
                    const BodyState* start, WallClearance* clearance, BodyState* b, State* st) {
  StepEnd end;
  if (out != StepOutcome::Ok) {
    // exited or failed: stopped where the step began (or landed where it would have met the
    // ground), at rest
    if (stop_body(model, type, i, t, out, reason, b, st) == BodyStatus::Landed) {
      b->v.setZero();
      b->w.setZero();
      end.moved = true;
    }
    end.next = AfterStep::Stopped;
    return end;
  }
  if (model.contacts()) {
    if (!near) {
      mark_flying(st, i);
    } else {
      const bool first_touch = std::isnan(st->t_touch[i]);
      const BodyState at_end = *b;
      const bool asleep =
          contact_after_step(model, type, i, t + model.dt, b, st, clearance, start);
      // the first ground touchdown, recorded at the step's end, moved to where it happened
      if (first_touch && start && !std::isnan(st->t_touch[i]))
        record_touchdown(model, type, i, t, *start, at_end, st);
      end.moved = b->x != at_end.x;  // (the sample depends on the position alone)
      if (asleep) {
        end.next = AfterStep::Asleep;
        end.wake = watch_sleeper(model, st, i, last);
        return end;
      }
    }
    // a colliding ground holds the body up: it never lands
    if (model.ground_collides()) return end;
  }
  if (!model.has_ground) return end;
  const bool land = landed ? *landed : touches_ground(model, type, *b);
  if (!land) return end;
  st->status[i] = BodyStatus::Landed;
  st->t_stop[i] = t + locate_touchdown(model, type, start ? *start : *b, *b, b);
  b->v.setZero();
  b->w.setZero();
  end.moved = true;
  end.next = AfterStep::Stopped;
  return end;
}

}  // namespace lrigid
