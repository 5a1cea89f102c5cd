// The robot's error flags and modes in words (franka_errors.hpp).

#include "comply/franka/franka_errors.hpp"

namespace comply::franka {
namespace {

struct ErrorText {
  const char* name;
  const char* stop;  // the FAULT text
};

// In the order of the flags on the wire. Reflexes and limits are cleared by the robot's
// automatic error recovery, which a reset runs.
constexpr std::array<ErrorText, fci::kErrorCount> kErrors{{
    {"joint_position_limits_violation",
     "joint_position_limits_violation (a joint at its limit): reset to recover, then move "
     "it away"},
    {"cartesian_position_limits_violation",
     "cartesian_position_limits_violation (the flange outside its workspace): reset to "
     "recover"},
    {"self_collision_avoidance_violation",
     "self_collision_avoidance_violation (the arm close to itself): reset to recover"},
    {"joint_velocity_violation",
     "joint_velocity_violation (a joint above its speed limit): reset to recover"},
    {"cartesian_velocity_violation",
     "cartesian_velocity_violation (the flange above its speed limit): reset to recover"},
    {"force_control_safety_violation", "force_control_safety_violation: reset to recover"},
    {"joint_reflex",
     "reflex joint_reflex (a joint's external torque above its collision threshold): "
     "reset to recover; raise collision_torque_n_m for intended contact"},
    {"cartesian_reflex",
     "reflex cartesian_reflex (the external force above its collision threshold): reset "
     "to recover; raise collision_force_n for intended contact"},
    {"max_goal_pose_deviation_violation", "max_goal_pose_deviation_violation: reset"},
    {"max_path_pose_deviation_violation", "max_path_pose_deviation_violation: reset"},
    {"cartesian_velocity_profile_safety_violation",
     "cartesian_velocity_profile_safety_violation: reset"},
    {"joint_position_motion_generator_start_pose_invalid",
     "joint_position_motion_generator_start_pose_invalid: reset"},
    {"joint_motion_generator_position_limits_violation",
     "joint_motion_generator_position_limits_violation: reset"},
    {"joint_motion_generator_velocity_limits_violation",
     "joint_motion_generator_velocity_limits_violation: reset"},
    {"joint_motion_generator_velocity_discontinuity",
     "joint_motion_generator_velocity_discontinuity: reset"},
    {"joint_motion_generator_acceleration_discontinuity",
     "joint_motion_generator_acceleration_discontinuity: reset"},
    {"cartesian_position_motion_generator_start_pose_invalid",
     "cartesian_position_motion_generator_start_pose_invalid: reset"},
    {"cartesian_motion_generator_elbow_limit_violation",
     "cartesian_motion_generator_elbow_limit_violation: reset"},
    {"cartesian_motion_generator_velocity_limits_violation",
     "cartesian_motion_generator_velocity_limits_violation: reset"},
    {"cartesian_motion_generator_velocity_discontinuity",
     "cartesian_motion_generator_velocity_discontinuity: reset"},
    {"cartesian_motion_generator_acceleration_discontinuity",
     "cartesian_motion_generator_acceleration_discontinuity: reset"},
    {"cartesian_motion_generator_elbow_sign_inconsistent",
     "cartesian_motion_generator_elbow_sign_inconsistent: reset"},
    {"cartesian_motion_generator_start_elbow_invalid",
     "cartesian_motion_generator_start_elbow_invalid: reset"},
    {"force_controller_desired_force_tolerance_violation",
     "force_controller_desired_force_tolerance_violation: reset"},
    {"start_elbow_sign_inconsistent", "start_elbow_sign_inconsistent: reset"},
    {"communication_constraints_violation",
     "communication_constraints_violation (the robot went without comply's torques for "
     "too many cycles in a row): check the network and the real-time kernel, then reset"},
    {"power_limit_violation",
     "power_limit_violation (the torques' power above the robot's limit): reset"},
    {"cartesian_motion_generator_joint_position_limits_violation",
     "cartesian_motion_generator_joint_position_limits_violation: reset"},
    {"cartesian_motion_generator_joint_velocity_limits_violation",
     "cartesian_motion_generator_joint_velocity_limits_violation: reset"},
    {"cartesian_motion_generator_joint_velocity_discontinuity",
     "cartesian_motion_generator_joint_velocity_discontinuity: reset"},
    {"cartesian_motion_generator_joint_acceleration_discontinuity",
     "cartesian_motion_generator_joint_acceleration_discontinuity: reset"},
    {"cartesian_position_motion_generator_invalid_frame",
     "cartesian_position_motion_generator_invalid_frame: reset"},
    {"controller_torque_discontinuity",
     "controller_torque_discontinuity (comply's torque jumped between two cycles more "
     "than the robot allows): reset"},
    {"joint_p2p_insufficient_torque_for_planning",
     "joint_p2p_insufficient_torque_for_planning: reset"},
    {"tau_J_range_violation", "tau_J_range_violation (a joint torque sensor out of range): reset"},
    {"instability_detected", "instability_detected: reset"},
    {"joint_move_in_wrong_direction", "joint_move_in_wrong_direction: reset"},
    {"cartesian_spline_motion_generator_violation",
     "cartesian_spline_motion_generator_violation: reset"},
    {"joint_via_motion_generator_planning_joint_limit_violation",
     "joint_via_motion_generator_planning_joint_limit_violation: reset"},
    {"base_acceleration_initialization_timeout", "base_acceleration_initialization_timeout: reset"},
    {"base_acceleration_invalid_reading", "base_acceleration_invalid_reading: reset"},
}};

}  // namespace

const char* errorName(int index) noexcept {
  return index >= 0 && index < fci::kErrorCount ? kErrors[static_cast<std::size_t>(index)].name
                                                : "";
}

std::string errorNames(const std::array<bool, fci::kErrorCount>& flags) {
  std::string names;
  for (int index = 0; index < fci::kErrorCount; ++index) {
    if (flags[static_cast<std::size_t>(index)]) {
      names += (names.empty() ? "" : ", ");
      names += errorName(index);
    }
  }
  return names;
}

const char* stopText(const std::array<bool, fci::kErrorCount>& flags,
                     fci::RobotMode mode) noexcept {
  if (mode == fci::RobotMode::kIdle || mode == fci::RobotMode::kMove) {
    // An error flag with the robot in Idle or Move is not a stop: the robot clears the flags
    // when it leaves Reflex.
    return nullptr;
  }
  for (std::size_t index = 0; index < flags.size(); ++index) {
    if (flags[index]) {
      return kErrors[index].stop;
    }
  }
  switch (mode) {
    case fci::RobotMode::kReflex:
      return "reflex (the robot named no reason): reset to recover";
    case fci::RobotMode::kUserStopped:
      return "user stop (the external activation device is pressed): release it, then "
             "reset";
    case fci::RobotMode::kGuiding:
      return "guiding (the pilot's guiding button is held): release it, then reset";
    case fci::RobotMode::kAutomaticErrorRecovery:
      return "recovering from an error";
    case fci::RobotMode::kOther:
      return "not ready (mode Other: the brakes closed or the joints not unlocked in "
             "Desk; FCI not activated)";
    case fci::RobotMode::kIdle:
    case fci::RobotMode::kMove:
      break;
  }
  return nullptr;
}

}  // namespace comply::franka
