// Stage "contact speed" (contact_speed.hpp): the TCP's speed along its motion bounded by what a
// contact there may cost. After the governor, so that the tighter of the two bounds the law's
// push, and before the walls' barrier, whose braking it never scales. Off (the default), one
// branch.

#include "comply/pipeline/controller.hpp"

namespace comply::pipeline {

void Controller::limitContactSpeed() noexcept {
  slowed_ = false;
  if (!contact_speed_.enabled()) {
    return;
  }
  slowed_ = contact_speed_.apply(data_, tcp_twist_, period_s_, law_torque_, torque_);
  if (slowed_) {
    diagnostics_.contact_speed_hits.fetch_add(1, std::memory_order_relaxed);
  }
}

}  // namespace comply::pipeline
