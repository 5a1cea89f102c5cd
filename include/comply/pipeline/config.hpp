#pragma once
// Wrapper configuration, read from a YAML file shaped like a ros2_control controller file:
//
//   <controller_name>:
//     ros__parameters:
//       plugin: cartesian_impedance          # plugin name or .so path
//       robot: fr3                           # robot name or folder (robots/<name>)
//       ...                                  # every key below, with its default
//
// Every option has a default that is safe on a real arm; units are in the key or the comment.

#include <filesystem>
#include <string>
#include <vector>

#include "comply/core/commands.hpp"
#include "comply/model/data.hpp"
#include "comply/plugin/loader.hpp"

namespace comply::pipeline {

enum class TimeoutBehavior { kHold, kReanchor };
enum class FrictionModel { kNone, kSigmoid, kViscousCoulomb };

struct FrictionConfig {
  FrictionModel model = FrictionModel::kNone;
  std::vector<double> phi1, phi2, phi3;  ///< sigmoid [N m], [s/rad], [rad/s]; default robot.yaml
  std::vector<double> viscous;           ///< N m s/rad
  std::vector<double> coulomb;           ///< N m
  double smoothing_velocity = 0.01;      ///< rad/s: tanh(dq / v) replaces sign(dq)
};

struct SoftLimitConfig {
  bool enabled = true;
  std::vector<double> margin;     ///< rad before the URDF limit where the spring starts
  std::vector<double> stiffness;  ///< N m/rad
  std::vector<double> damping;    ///< N m s/rad
};

struct ValidationConfig {
  double quaternion_tolerance = 1e-3;      ///< |norm - 1| renormalised below, rejected above
  double max_position_jump_m = 0.10;       ///< target vs measured TCP position
  double max_orientation_jump_rad = 0.60;  ///< target vs measured TCP orientation
  double max_joint_jump_rad = 0.50;        ///< joint target vs measured position
  double gain_tolerance = 1e-9;            ///< symmetry / PSD tolerance, relative
};

struct WrapperConfig {
  std::string name;  ///< controller name (top-level YAML key)
  std::string plugin;
  plugin::ParameterMap plugin_parameters;
  std::string robot;                ///< name or folder
  std::vector<std::string> joints;  ///< default: robot.yaml joints
  std::string base_frame;           ///< default: robot.yaml base_frame
  std::string tip_frame;            ///< default: robot.yaml tcp_frame
  int dof = 0;                      ///< number of joints (from `joints`)

  double command_timeout_s = 0.5;
  TimeoutBehavior timeout_behavior = TimeoutBehavior::kHold;
  ValidationConfig validation;

  bool gravity_compensation = true;
  bool payload_compensation = false;
  model::Payload payload;
  FrictionConfig friction;
  SoftLimitConfig soft_limits;

  double filter_alpha = 1.0;              ///< tau_f = alpha tau + (1 - alpha) tau_f,prev; 1 = off
  std::vector<double> torque_rate_limit;  ///< N m/s per joint
  std::vector<double> effort_limit;       ///< N m; default: URDF <limit effort>
  std::vector<double> fault_damping;      ///< N m s/rad of the safe holding torque

  /// Initial command (gains, task frame); the pose/joint reference is seeded on activation.
  JointCommand initial_joint;
  CartesianCommand initial_cartesian;
};

/// Reads `controller_name` (or the only controller in the file when empty) from a YAML file.
/// Per-joint lists accept one number (applied to every joint) or one per joint. Throws
/// std::runtime_error naming the file and the key on any error.
WrapperConfig loadWrapperConfig(const std::filesystem::path& file,
                                const std::string& controller_name = {});

/// Same from YAML text (`source` names it in messages).
WrapperConfig parseWrapperConfig(const std::string& yaml_text, const std::string& source,
                                 const std::string& controller_name = {});

}  // namespace comply::pipeline
