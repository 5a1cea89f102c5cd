#pragma once
// The command schema: one line per field, in the order of the plugin buses (plugin/abi.h). Every
// other spelling of the schema is derived from these tables: the members of the C++ commands
// (core/commands.hpp), bus conversion, merging, reference rules, validation, JSON and YAML
// reading and writing, and the ROS 2 messages and docs/command-schema.md (`comply schema`).
// Adding a field is one line here plus the member of the C bus struct in plugin/abi.h.
//
// This header holds macros only, so that core can include it without depending on anything.
//
// X(name, group, kind, type, unit, constraint, role, init, description)
//   name        C++ member = bus member = JSON key
//   group       CommandField enumerator the field travels with (one mask bit per group)
//   kind        schema::FieldKind: kVector3, kVector6, kJointVector (dof entries), kBlock3 (3x3
//               gain block, row-major on the bus and in JSON), kQuaternion (x y z w), kEnum
//   type        C++ member type (no top-level comma)
//   unit        SI unit, "" for none
//   constraint  schema::Constraint checked on every command that sets the group: kNone,
//               kNonNegative, kSymmetricPsd, kUnitQuaternion (drift renormalised), kSelection
//               (every entry 0 or 1), kThreshold (every entry >= 0; 0: the controller file's)
//   role        schema::Role in the reference rules: kSeedTcpPosition, kSeedTcpOrientation,
//               kSeedJointPosition (set from the measured state when a reference is seeded),
//               kZeroOnStop (zeroed when seeding and when motion stops), kNone
//   init        default member initialiser
//   description one line for the docs and messages

// Field groups: X(enumerator, name as in JSON `fields` lists, meaning).
#define COMPLY_COMMAND_FIELD_GROUPS(X)                                             \
  X(kPosition, "position", "joint position | Cartesian position and orientation")  \
  X(kVelocity, "velocity", "joint velocity | Cartesian twist")                     \
  X(kAcceleration, "acceleration", "joint | Cartesian acceleration")               \
  X(kStiffness, "stiffness", "joint stiffness | both Cartesian stiffness blocks")  \
  X(kDamping, "damping", "joint damping | Cartesian damping blocks, mode, ratios") \
  X(kTaskFrame, "task_frame", "Cartesian task-frame orientation")                  \
  X(kWrenchFeedforward, "wrench_feedforward", "Cartesian wrench feedforward")      \
  X(kTorqueFeedforward, "torque_feedforward", "joint torque feedforward")          \
  X(kNullspace, "nullspace", "nullspace target, stiffness and damping")            \
  X(kForce, "force", "force-controlled task axes and their wrench target")         \
  X(kReflex, "reflex", "the contact reflex's thresholds for this phase of the task")     \
  X(kWorkspace, "workspace", "a box the TCP stays inside for this phase of the task")

// The contact reflex's thresholds (pipeline/contact_reflex.hpp), the same rows in both tables;
// `frame` names the axes: the task frame's (Cartesian), the base frame's (joint).
#define COMPLY_REFLEX_COMMAND_FIELDS(X, frame)                                                  \
  X(reflex_force, kReflex, kVector3, Eigen::Vector3d, "N", kThreshold, kNone,                   \
    Eigen::Vector3d::Zero(),                                                                    \
    "contact force per " frame " axis (x y z) above which the reflex trips; 0: reflex.force_n") \
  X(reflex_torque, kReflex, kVector3, Eigen::Vector3d, "N m", kThreshold, kNone,                \
    Eigen::Vector3d::Zero(),                                                                    \
    "contact torque per " frame " axis (x y z) above which the reflex trips; 0: reflex.torque_nm")

#define COMPLY_CARTESIAN_COMMAND_FIELDS(X)                                                       \
  X(position, kPosition, kVector3, Eigen::Vector3d, "m", kNone, kSeedTcpPosition,                \
    Eigen::Vector3d::Zero(), "TCP target, base frame")                                           \
  X(orientation, kPosition, kQuaternion, Eigen::Quaterniond, "", kUnitQuaternion,                \
    kSeedTcpOrientation, Eigen::Quaterniond::Identity(), "TCP target orientation, base frame")   \
  X(twist, kVelocity, kVector6, Vector6d, "m/s, rad/s", kNone, kZeroOnStop, Vector6d::Zero(),    \
    "target TCP velocity, base frame, linear first")                                             \
  X(acceleration, kAcceleration, kVector6, Vector6d, "m/s^2, rad/s^2", kNone, kZeroOnStop,       \
    Vector6d::Zero(), "target TCP acceleration, base frame, linear first")                       \
  X(stiffness_translational, kStiffness, kBlock3, Eigen::Matrix3d, "N/m", kSymmetricPsd, kNone,  \
    Eigen::Matrix3d::Zero(), "translational stiffness in the task frame")                        \
  X(stiffness_rotational, kStiffness, kBlock3, Eigen::Matrix3d, "N m/rad", kSymmetricPsd, kNone, \
    Eigen::Matrix3d::Zero(), "rotational stiffness in the task frame")                           \
  X(damping_translational, kDamping, kBlock3, Eigen::Matrix3d, "N s/m", kSymmetricPsd, kNone,    \
    Eigen::Matrix3d::Zero(), "translational damping in the task frame (absolute mode)")          \
  X(damping_rotational, kDamping, kBlock3, Eigen::Matrix3d, "N m s/rad", kSymmetricPsd, kNone,   \
    Eigen::Matrix3d::Zero(), "rotational damping in the task frame (absolute mode)")             \
  X(damping_mode, kDamping, kEnum, DampingMode, "", kNone, kNone, DampingMode::kAbsolute,        \
    "absolute: damping blocks as sent; ratio: damping_ratio against the Cartesian inertia")      \
  X(damping_ratio, kDamping, kVector6, Vector6d, "1", kNonNegative, kNone, Vector6d::Ones(),     \
    "damping ratio per task axis (x y z rx ry rz), 1 = critical (ratio mode)")                   \
  X(task_frame, kTaskFrame, kQuaternion, Eigen::Quaterniond, "", kUnitQuaternion, kNone,         \
    Eigen::Quaterniond::Identity(), "task-frame orientation in the base frame")                  \
  X(wrench_feedforward, kWrenchFeedforward, kVector6, Vector6d, "N, N m", kNone, kNone,          \
    Vector6d::Zero(), "feedforward wrench, base frame, force first")                             \
  X(torque_feedforward, kTorqueFeedforward, kJointVector, JointVector, "N m", kNone, kNone,      \
    JointVector(), "feedforward joint torque")                                                   \
  X(nullspace_position, kNullspace, kJointVector, JointVector, "rad", kNone, kSeedJointPosition, \
    JointVector(), "joint target of the nullspace task")                                         \
  X(nullspace_stiffness, kNullspace, kJointVector, JointVector, "N m/rad", kNonNegative, kNone,  \
    JointVector(), "nullspace stiffness per joint")                                              \
  X(nullspace_damping, kNullspace, kJointVector, JointVector, "N m s/rad", kNonNegative, kNone,  \
    JointVector(), "nullspace damping per joint")                                                \
  X(force_axes, kForce, kVector6, Vector6d, "", kSelection, kZeroOnStop, Vector6d::Zero(),       \
    "1: a force-controlled task axis (x y z rx ry rz), 0: impedance")                            \
  X(wrench_target, kForce, kVector6, Vector6d, "N, N m", kNone, kNone, Vector6d::Zero(),         \
    "wrench the TCP exerts along the force axes, task frame, force first")                       \
  COMPLY_REFLEX_COMMAND_FIELDS(X, "task")                                                        \
  X(workspace_min, kWorkspace, kVector3, Eigen::Vector3d, "m", kNone, kNone,                     \
    Eigen::Vector3d::Zero(),                                                                     \
    "the box's lower corner, base frame, besides the controller file's walls; all 0 with "       \
    "workspace_max: none")                                                                       \
  X(workspace_max, kWorkspace, kVector3, Eigen::Vector3d, "m", kNone, kNone,                     \
    Eigen::Vector3d::Zero(), "the box's upper corner, base frame")

#define COMPLY_JOINT_COMMAND_FIELDS(X)                                                             \
  X(position, kPosition, kJointVector, JointVector, "rad | m", kNone, kSeedJointPosition,          \
    JointVector(), "joint target")                                                                 \
  X(velocity, kVelocity, kJointVector, JointVector, "rad/s | m/s", kNone, kZeroOnStop,             \
    JointVector(), "joint velocity target")                                                        \
  X(acceleration, kAcceleration, kJointVector, JointVector, "rad/s^2 | m/s^2", kNone, kZeroOnStop, \
    JointVector(), "joint acceleration target")                                                    \
  X(stiffness, kStiffness, kJointVector, JointVector, "N m/rad | N/m", kNonNegative, kNone,        \
    JointVector(), "joint stiffness")                                                              \
  X(damping, kDamping, kJointVector, JointVector, "N m s/rad | N s/m", kNonNegative, kNone,        \
    JointVector(), "joint damping")                                                                \
  X(torque_feedforward, kTorqueFeedforward, kJointVector, JointVector, "N m | N", kNone, kNone,    \
    JointVector(), "feedforward joint torque | force")                                             \
  COMPLY_REFLEX_COMMAND_FIELDS(X, "base frame")

/// Expands a table line into a C++ member declaration (core/commands.hpp).
#define COMPLY_SCHEMA_MEMBER(name, group, kind, type, unit, constraint, role, init, description) \
  type name = init;
