#include "comply/pipeline/plugin_input.hpp"

namespace comply::pipeline {
namespace {

using model::Quantity;

bool has(Quantity set, Quantity quantity) {
  return (set & quantity) != Quantity::kNone;
}

}  // namespace

model::Quantity quantitiesFor(std::uint32_t needs) noexcept {
  Quantity quantities = Quantity::kNone;
  const auto wants = [needs](std::uint32_t flag) { return (needs & flag) != 0; };
  if (wants(COMPLY_NEED_POSE)) {
    quantities = quantities | Quantity::kPose;
  }
  if (wants(COMPLY_NEED_JACOBIAN)) {
    quantities = quantities | Quantity::kPose | Quantity::kJacobian;
  }
  if (wants(COMPLY_NEED_MASS_MATRIX)) {
    quantities = quantities | Quantity::kMassMatrix;
  }
  if (wants(COMPLY_NEED_GRAVITY)) {
    quantities = quantities | Quantity::kGravity;
  }
  if (wants(COMPLY_NEED_CORIOLIS)) {
    quantities = quantities | Quantity::kCoriolis;
  }
  return quantities;
}

void fillPluginInput(const JointState& state, const model::Data& data, model::Quantity computed,
                     double time_s, double period_s, comply_input& input) noexcept {
  const auto dof = static_cast<int>(state.position.size());
  input.dof = dof;
  input.time_s = time_s;
  input.period_s = period_s;
  input.available = 0;
  for (int i = 0; i < dof; ++i) {
    input.position[i] = state.position[i];
    input.velocity[i] = state.velocity[i];
    input.effort[i] = state.effort[i];
  }
  if (has(computed, Quantity::kPose)) {
    input.available |= COMPLY_NEED_POSE;
    for (int k = 0; k < 3; ++k) {
      input.tcp_position[k] = data.tip_position[k];
    }
    input.tcp_orientation[0] = data.tip_orientation.x();
    input.tcp_orientation[1] = data.tip_orientation.y();
    input.tcp_orientation[2] = data.tip_orientation.z();
    input.tcp_orientation[3] = data.tip_orientation.w();
  }
  if (has(computed, Quantity::kJacobian)) {
    input.available |= COMPLY_NEED_JACOBIAN;
    for (int col = 0; col < dof; ++col) {
      for (int row = 0; row < 6; ++row) {
        input.jacobian[col * 6 + row] = data.jacobian(row, col);
      }
    }
  }
  if (has(computed, Quantity::kMassMatrix)) {
    input.available |= COMPLY_NEED_MASS_MATRIX;
    for (int col = 0; col < dof; ++col) {
      for (int row = 0; row < dof; ++row) {
        input.mass_matrix[col * COMPLY_MAX_DOF + row] = data.mass_matrix(row, col);
      }
    }
  }
  if (has(computed, Quantity::kGravity)) {
    input.available |= COMPLY_NEED_GRAVITY;
    for (int i = 0; i < dof; ++i) {
      input.gravity[i] = data.gravity[i];
    }
  }
  if (has(computed, Quantity::kCoriolis)) {
    input.available |= COMPLY_NEED_CORIOLIS;
    for (int i = 0; i < dof; ++i) {
      input.coriolis[i] = data.coriolis[i];
    }
  }
}

}  // namespace comply::pipeline
