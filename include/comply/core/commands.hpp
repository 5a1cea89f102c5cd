#pragma once
// The command schemas a user sends (DESIGN.md "Command schemas"). Field names are the same in the
// C buses (plugin/abi.h), JSON files and messages. Poses, twists and wrenches are in the base
// frame; gain blocks in the task frame, whose orientation travels with the command.

#include <Eigen/Geometry>
#include <cstdint>

#include "comply/core/capacity.hpp"

namespace comply {

using Vector6d = Eigen::Matrix<double, 6, 1>;

/// Field groups of a command; a sender sets only those it updates, the rest stays in force.
/// Bit values equal COMPLY_FIELD_* of the plugin ABI.
enum class CommandField : std::uint32_t {
  kNone = 0,
  kPosition = 1U << 0,      ///< joint position | Cartesian position + orientation
  kVelocity = 1U << 1,      ///< joint velocity | Cartesian twist
  kAcceleration = 1U << 2,  ///< joint | Cartesian acceleration
  kStiffness = 1U << 3,     ///< joint stiffness | both Cartesian stiffness blocks
  kDamping = 1U << 4,       ///< joint damping | Cartesian damping blocks, mode and ratios
  kTaskFrame = 1U << 5,     ///< Cartesian task-frame orientation
  kWrenchFeedforward = 1U << 6,
  kTorqueFeedforward = 1U << 7,
  kNullspace = 1U << 8,  ///< nullspace target, stiffness and damping
  kAll = (1U << 9) - 1,
};

constexpr CommandField operator|(CommandField a, CommandField b) {
  return static_cast<CommandField>(static_cast<std::uint32_t>(a) | static_cast<std::uint32_t>(b));
}
constexpr bool has(CommandField set, CommandField field) {
  return (static_cast<std::uint32_t>(set) & static_cast<std::uint32_t>(field)) != 0;
}

struct JointCommand {
  double stamp_s = 0.0;  ///< sender time [s]; must not go backwards
  CommandField fields = CommandField::kAll;
  JointVector position;            ///< rad | m
  JointVector velocity;            ///< rad/s | m/s
  JointVector acceleration;        ///< rad/s^2 | m/s^2
  JointVector stiffness;           ///< N m/rad | N/m, >= 0
  JointVector damping;             ///< N m s/rad | N s/m, >= 0
  JointVector torque_feedforward;  ///< N m | N

  /// All vectors sized `dof` and zero.
  static JointCommand zero(int dof);
};

enum class DampingMode : std::int32_t {
  kAbsolute = 0,  ///< damping blocks as sent
  kRatio = 1,     ///< damping ratios per task axis, turned into D against the Cartesian inertia
};

struct CartesianCommand {
  double stamp_s = 0.0;
  CommandField fields = CommandField::kAll;
  Eigen::Vector3d position = Eigen::Vector3d::Zero();                 ///< TCP target [m]
  Eigen::Quaterniond orientation = Eigen::Quaterniond::Identity();    ///< TCP target
  Vector6d twist = Vector6d::Zero();                                  ///< [m/s, rad/s]
  Vector6d acceleration = Vector6d::Zero();                           ///< [m/s^2, rad/s^2]
  Eigen::Matrix3d stiffness_translational = Eigen::Matrix3d::Zero();  ///< task frame [N/m]
  Eigen::Matrix3d stiffness_rotational = Eigen::Matrix3d::Zero();     ///< task frame [N m/rad]
  Eigen::Matrix3d damping_translational = Eigen::Matrix3d::Zero();    ///< task frame [N s/m]
  Eigen::Matrix3d damping_rotational = Eigen::Matrix3d::Zero();       ///< task frame [N m s/rad]
  DampingMode damping_mode = DampingMode::kAbsolute;
  Vector6d damping_ratio = Vector6d::Ones();  ///< per task axis (x y z rx ry rz)
  Eigen::Quaterniond task_frame = Eigen::Quaterniond::Identity();  ///< task axes in base frame
  Vector6d wrench_feedforward = Vector6d::Zero();                  ///< base frame [N, N m]
  JointVector torque_feedforward;                                  ///< N m
  JointVector nullspace_position;                                  ///< rad
  JointVector nullspace_stiffness;                                 ///< N m/rad, >= 0
  JointVector nullspace_damping;                                   ///< N m s/rad, >= 0

  /// Zero gains, identity orientations, joint vectors sized `dof`.
  static CartesianCommand zero(int dof);
};

}  // namespace comply
