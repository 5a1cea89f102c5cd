#pragma once
// Fills the plugin's input bus from the measured state and the model results. Shared by the
// execution core and host-side tools that call a law outside a wrapper, so both hand the law
// exactly the same numbers. Real-time safe.

#include "comply/core/state.hpp"
#include "comply/model/data.hpp"
#include "comply/plugin/abi.h"

namespace comply::pipeline {

/// The COMPLY_NEED_* flags as model quantities (the Jacobian implies the pose).
model::Quantity quantitiesFor(std::uint32_t needs) noexcept;

/// Copies state and the quantities in `computed` from `data` into `input` (dof entries; jacobian
/// column-major with leading dimension 6, mass matrix with leading dimension COMPLY_MAX_DOF).
/// `input.available` is set to the COMPLY_NEED_* flags those quantities satisfy.
void fillPluginInput(const JointState& state, const model::Data& data, model::Quantity computed,
                     double time_s, double period_s, comply_input& input) noexcept;

}  // namespace comply::pipeline
