#pragma once
// Commands as JSON objects, with the field names of the command schema (DESIGN.md): quaternions
// [x, y, z, w], 3x3 gain blocks as 9 numbers row-major, twists and wrenches linear first.
//
//   {"stamp": 0.1, "fields": ["stiffness"], "stiffness_translational": [...], ...}
//
// `fields` lists the field groups the command sets (position, velocity, acceleration, stiffness,
// damping, task_frame, wrench_feedforward, torque_feedforward, nullspace); without it, the groups
// whose keys are present. Keys of a group that are absent keep the value of `base`.

#include <nlohmann/json_fwd.hpp>
#include <stdexcept>
#include <string>

#include "comply/core/commands.hpp"

namespace comply::app {

/// Thrown for unknown keys, wrong lengths, wrong types; the message names the key.
class CommandJsonError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

JointCommand commandFromJson(const nlohmann::json& object, int dof, const JointCommand& base);
CartesianCommand commandFromJson(const nlohmann::json& object, int dof,
                                 const CartesianCommand& base);

}  // namespace comply::app
