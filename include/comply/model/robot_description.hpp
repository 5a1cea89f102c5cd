#pragma once
// A robot folder: `<name>/robot.yaml` + its URDF. Commands that take a robot accept either a name
// found on the robot search path or a path to such a folder, so users add robots without code.

#include <filesystem>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "comply/model/model.hpp"

namespace comply::model {

/// Joint friction tau_f = phi1 / (1 + exp(-phi2 (dq + phi3))) - phi1 / (1 + exp(-phi2 phi3))
/// (Gaz et al., RA-L 2019), one entry per joint.
struct SigmoidFriction {
  std::vector<double> phi1;  ///< N m
  std::vector<double> phi2;  ///< s/rad
  std::vector<double> phi3;  ///< rad/s
};

/// Plant parameters a simulator gives each joint, so that compensation has something to do. The
/// rotor inertias are the arm's too: the controller's M(q) carries them (ModelOptions::armature).
struct JointDynamics {
  std::vector<double> damping;       ///< viscous [N m s/rad]
  std::vector<double> armature;      ///< reflected rotor inertia [kg m^2]
  std::vector<double> frictionloss;  ///< Coulomb [N m]
};

struct RobotDescription {
  std::string name;
  std::string description;
  std::filesystem::path folder;
  std::filesystem::path urdf_path;
  /// The URDF text when it came from elsewhere than urdf_path (a ROS 2 `robot_description`);
  /// the model is then built from this text, the robot.yaml still gives joints, frames, friction.
  std::string urdf_xml;
  std::vector<std::string> joints;  ///< controlled joints, base to tip
  std::string base_frame;
  std::string flange_frame;
  std::string tcp_frame;
  std::vector<double> home;  ///< rad | m, in `joints` order
  std::optional<SigmoidFriction> friction;
  std::optional<JointDynamics> joint_dynamics;

  /// Model options for a chain from base_frame to `tip` (default: tcp_frame).
  [[nodiscard]] ModelOptions modelOptions(const std::string& tip = {}) const;
  /// Loads the URDF (urdf_xml if set, else urdf_path) and builds the model for base_frame -> tip
  /// (default: tcp_frame).
  [[nodiscard]] Model loadModel(const std::string& tip = {}) const;
  /// The same for explicit options (joints, base frame chosen by a controller configuration).
  [[nodiscard]] Model loadModel(const ModelOptions& options) const;
};

/// Folders searched for robot names, in order: each entry of $COMPLY_ROBOT_PATH (':'-separated),
/// then the robots folder of this installation.
std::vector<std::filesystem::path> robotSearchPath();

/// Names of the robots found on the search path (folders holding a robot.yaml), sorted.
std::vector<std::string> availableRobots();

/// Loads a robot by name (searched on robotSearchPath()) or by folder path (anything containing
/// a '/' or naming an existing folder). Throws ModelError with the robots available when unknown.
RobotDescription loadRobotDescription(std::string_view name_or_path);

}  // namespace comply::model
