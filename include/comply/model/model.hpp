#pragma once
// A serial kinematic chain extracted from a URDF: the constant half of the model (Featherstone's
// "model"); per-update results and scratch live in comply::model::Data, so one Model can serve any
// number of Data objects (threads, simulated copies) without copying.

#include <Eigen/Geometry>
#include <array>
#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

#include "comply/core/capacity.hpp"

namespace comply::model {

/// What the caller wants from a URDF: which joints it controls and which frame it tracks.
struct ModelOptions {
  /// Controlled joints by name, in the order the caller uses for q, dq and torques. Every movable
  /// joint between base_frame and tip_frame must be listed; the order is free.
  std::vector<std::string> joint_names;
  /// Link the results are expressed in; empty = the URDF root link.
  std::string base_frame;
  /// Link whose pose and Jacobian are computed (any link below base_frame; fixed joints are folded).
  std::string tip_frame;
  /// Extra fixed offset from tip_frame to the tool centre point, expressed in tip_frame.
  Eigen::Isometry3d tcp_offset = Eigen::Isometry3d::Identity();
  /// Gravitational acceleration in base_frame axes [m/s^2].
  Eigen::Vector3d gravity_m_per_s2{0.0, 0.0, -9.81};
  /// Reflected rotor inertia of each joint [kg m^2 | kg], in joint_names order: what a geared
  /// drive accelerates besides the links (robot.yaml joint_dynamics.armature), added to the
  /// diagonal of M(q) as MuJoCo's dof_armature is. Empty: the bare links of the URDF.
  std::vector<double> armature;
};

enum class JointType { kRevolute, kPrismatic };

/// Limits of one controlled joint as written in the URDF; continuous joints have +-infinity bounds.
struct JointLimits {
  double lower = 0.0;     ///< rad or m
  double upper = 0.0;     ///< rad or m
  double velocity = 0.0;  ///< rad/s or m/s
  double effort = 0.0;    ///< N m or N
};

/// One moving body of the chain: the link after a controlled joint together with every link that
/// is rigidly attached to it (fixed joints, off-chain branches locked at zero).
struct ChainBody {
  JointType type = JointType::kRevolute;
  /// Rotation of the joint frame in the previous body's frame, pre-multiplied into the Rodrigues
  /// terms so that R_parent_body = rotation_const + sin(q) rotation_sin + (1 - cos(q)) rotation_cos.
  Eigen::Matrix3d rotation_const = Eigen::Matrix3d::Identity();
  Eigen::Matrix3d rotation_sin = Eigen::Matrix3d::Zero();
  Eigen::Matrix3d rotation_cos = Eigen::Matrix3d::Zero();
  /// Joint frame origin in the previous body's frame [m].
  Eigen::Vector3d translation = Eigen::Vector3d::Zero();
  /// Unit joint axis in the joint (= body) frame.
  Eigen::Vector3d axis = Eigen::Vector3d::UnitZ();
  /// Joint axis in the previous body's frame (rotation_const * axis), for prismatic offsets.
  Eigen::Vector3d axis_in_parent = Eigen::Vector3d::UnitZ();
  double mass_kg = 0.0;
  /// Centre of mass in the body frame [m].
  Eigen::Vector3d com = Eigen::Vector3d::Zero();
  /// Rotational inertia about the centre of mass, body-frame axes [kg m^2].
  Eigen::Matrix3d inertia_com = Eigen::Matrix3d::Zero();
  /// Index of this joint in ModelOptions::joint_names (the caller's order).
  int user_index = 0;
  /// Reflected rotor inertia on this joint [kg m^2 | kg] (ModelOptions::armature).
  double armature = 0.0;
};

class Model {
 public:
  /// Builds the chain from a URDF file. Throws ModelError naming the file, joint or frame at fault.
  static Model fromUrdfFile(const std::filesystem::path& urdf_path, const ModelOptions& options);
  /// Same from URDF text (e.g. a robot_description parameter).
  static Model fromUrdfString(std::string_view urdf_xml, const ModelOptions& options);

  [[nodiscard]] int dof() const noexcept { return dof_; }
  /// Controlled joint names in the caller's order.
  [[nodiscard]] const std::vector<std::string>& jointNames() const noexcept { return joint_names_; }
  [[nodiscard]] const std::string& baseFrame() const noexcept { return base_frame_; }
  [[nodiscard]] const std::string& tipFrame() const noexcept { return tip_frame_; }
  /// Limits in the caller's joint order.
  [[nodiscard]] const JointLimits& limits(int joint_index) const { return limits_.at(joint_index); }
  [[nodiscard]] const Eigen::Vector3d& gravity() const noexcept { return gravity_; }
  /// The rotor inertias in M(q), in the caller's joint order; empty: none (bare links).
  [[nodiscard]] const std::vector<double>& armature() const noexcept { return armature_; }

  /// Bodies in chain order (base to tip); body i moves with controlled joint bodies()[i].user_index.
  [[nodiscard]] const ChainBody& body(int chain_index) const noexcept { return bodies_[chain_index]; }
  /// Tip frame (including the TCP offset) in the last body's frame.
  [[nodiscard]] const Eigen::Isometry3d& tipInLastBody() const noexcept { return tip_in_last_body_; }
  /// True when the caller's joint order equals chain order (then no index mapping is needed).
  [[nodiscard]] bool jointOrderIsChainOrder() const noexcept { return order_is_chain_order_; }

 private:
  Model() = default;
  friend class ModelBuilder;

  int dof_ = 0;
  std::array<ChainBody, kMaxDof> bodies_{};
  std::vector<std::string> joint_names_;
  std::vector<JointLimits> limits_;
  std::vector<double> armature_;
  std::string base_frame_;
  std::string tip_frame_;
  Eigen::Isometry3d tip_in_last_body_ = Eigen::Isometry3d::Identity();
  Eigen::Vector3d gravity_{0.0, 0.0, -9.81};
  bool order_is_chain_order_ = true;
};

}  // namespace comply::model
