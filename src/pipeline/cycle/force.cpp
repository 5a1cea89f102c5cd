// Stage "force": force along the task axes a command selects, and the contact-force limit
// (force_axes.hpp), on what the gain stage let through. Only a Cartesian law has task axes; a
// command that selects none, without a limit configured, costs one branch and a scan of six
// numbers, and the law reads the gain stage's command itself. What the stage commands (the force
// loop's push and the feedforward) is kept within what the arm exerts at this pose
// (wrench_bound.hpp).

#include "comply/pipeline/controller.hpp"
#include "comply/pipeline/wrench_bound.hpp"

namespace comply::pipeline {

void Controller::applyForce() noexcept {
  force_active_ = false;
  const auto* in = std::get_if<comply_cartesian_command>(&guardedBus());
  auto* out = std::get_if<comply_cartesian_command>(&force_bus_);
  if (in == nullptr || out == nullptr) {
    return;
  }
  if (!force_.acts(*in)) {
    force_.reset();
    return;
  }
  force_.apply(*in, data_, tcp_twist_, contactWrench(parameters_.force_control.source), period_s_,
               *out);
  (void)boundWrench(data_.jacobian, out->wrench_feedforward, parameters_.effort_limit, dof_);
  force_active_ = true;
}

const Vector6d* Controller::contactWrench(ForceSource source) const noexcept {
  const bool observer = observer_.enabled() && source != ForceSource::kSensor;
  if (observer) {
    return &observer_.wrench();
  }
  if (source != ForceSource::kObserver && wrist_.valid()) {
    return &wrist_.wrench();
  }
  return nullptr;
}

}  // namespace comply::pipeline
