#pragma once
// Measured joint state as read from hardware (real or simulated).

#include "comply/core/capacity.hpp"

namespace comply {

struct JointState {
  JointVector position;  ///< rad | m
  JointVector velocity;  ///< rad/s | m/s
  JointVector effort;    ///< measured torque, N m | N

  static JointState zero(int dof) {
    JointState state;
    state.position.setZero(dof);
    state.velocity.setZero(dof);
    state.effort.setZero(dof);
    return state;
  }
};

}  // namespace comply
