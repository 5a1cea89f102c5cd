#include "comply/pipeline/config.hpp"

#include <yaml-cpp/yaml.h>

#include <algorithm>
#include <fstream>
#include <set>
#include <sstream>
#include <stdexcept>
#include <utility>

#include "comply/model/robot_description.hpp"

namespace comply::pipeline {
namespace {

/// Reads one YAML mapping, remembering which keys were used so typos are reported.
class Section {
 public:
  Section(YAML::Node node, std::string path, const std::string& source)
      : node_(std::move(node)), path_(std::move(path)), source_(source) {
    if (node_ && !node_.IsMap()) {
      fail("must be a mapping");
    }
  }

  [[noreturn]] void fail(const std::string& message, const std::string& key = {}) const {
    throw std::runtime_error(source_ + ": " + (key.empty() ? path_ : path_ + "." + key) + " " +
                             message);
  }

  /// The value at `key`; an undefined node (false in a condition) when absent. A default-made
  /// YAML::Node would not do: it is a defined null, which reads as "present, wrong type".
  YAML::Node get(const std::string& key) {
    used_.insert(key);
    static const YAML::Node kEmptyMap(YAML::NodeType::Map);
    const YAML::Node& lookup = node_ ? node_ : kEmptyMap;
    return lookup[key];  // const lookup: never inserts the key
  }

  Section section(const std::string& key) { return {get(key), path_ + "." + key, source_}; }

  template <typename T>
  T value(const std::string& key, const T& fallback) {
    const YAML::Node node = get(key);
    if (!node) {
      return fallback;
    }
    try {
      return node.as<T>();
    } catch (const YAML::Exception&) {
      fail("has the wrong type", key);
    }
  }

  std::string required(const std::string& key) {
    const YAML::Node node = get(key);
    if (!node || !node.IsScalar()) {
      fail("is required", key);
    }
    return node.as<std::string>();
  }

  /// One number for all, or `count` numbers; `fallback` when absent.
  std::vector<double> perJoint(const std::string& key, int count,
                               const std::vector<double>& fallback) {
    const YAML::Node node = get(key);
    if (!node) {
      return fallback;
    }
    std::vector<double> values;
    try {
      values = node.IsSequence() ? node.as<std::vector<double>>()
                                 : std::vector<double>(count, node.as<double>());
    } catch (const YAML::Exception&) {
      fail("must be a number or a list of numbers", key);
    }
    if (static_cast<int>(values.size()) != count) {
      fail("has " + std::to_string(values.size()) + " values, expected 1 or " +
               std::to_string(count),
           key);
    }
    return values;
  }

  /// A 3x3 gain block: 1 number (isotropic), 3 (diagonal) or 9 (row-major).
  Eigen::Matrix3d block(const std::string& key, const Eigen::Matrix3d& fallback) {
    const YAML::Node node = get(key);
    if (!node) {
      return fallback;
    }
    std::vector<double> values;
    try {
      values = node.IsSequence() ? node.as<std::vector<double>>()
                                 : std::vector<double>{node.as<double>()};
    } catch (const YAML::Exception&) {
      fail("must be a number or a list of numbers", key);
    }
    switch (values.size()) {
      case 1:
        return values[0] * Eigen::Matrix3d::Identity();
      case 3:
        return Eigen::Vector3d(values[0], values[1], values[2]).asDiagonal();
      case 9:
        return Eigen::Map<const Eigen::Matrix<double, 3, 3, Eigen::RowMajor>>(values.data());
      default:
        fail("needs 1, 3 or 9 values", key);
    }
  }

  void rejectUnknownKeys() const {
    if (!node_) {
      return;
    }
    for (const auto& entry : node_) {
      const auto key = entry.first.as<std::string>();
      if (used_.count(key) == 0) {
        fail("is not a known option", key);
      }
    }
  }

 private:
  YAML::Node node_;
  std::string path_;
  const std::string& source_;
  std::set<std::string> used_;
};

plugin::ParameterMap readPluginParameters(Section& section, const std::string& source) {
  plugin::ParameterMap parameters;
  const YAML::Node node = section.get("plugin_parameters");
  if (!node) {
    return parameters;
  }
  if (!node.IsMap()) {
    section.fail("must be a mapping", "plugin_parameters");
  }
  for (const auto& entry : node) {
    plugin::ParameterValue value;
    const auto name = entry.first.as<std::string>();
    try {
      if (entry.second.IsSequence()) {
        value.numbers = entry.second.as<std::vector<double>>();
      } else {
        try {
          value.numbers = {entry.second.as<double>()};
        } catch (const YAML::Exception&) {
          value.text = entry.second.as<std::string>();
          value.is_text = true;
        }
      }
    } catch (const YAML::Exception&) {
      throw std::runtime_error(source + ": plugin_parameters." + name +
                               " must be a number, a list of numbers or a string");
    }
    parameters[name] = value;
  }
  return parameters;
}

Eigen::Quaterniond readQuaternion(Section& section, const std::string& key) {
  const YAML::Node node = section.get(key);
  if (!node) {
    return Eigen::Quaterniond::Identity();
  }
  std::vector<double> xyzw;
  try {
    xyzw = node.as<std::vector<double>>();
  } catch (const YAML::Exception&) {
    section.fail("must be [x, y, z, w]", key);
  }
  if (xyzw.size() != 4) {
    section.fail("must be [x, y, z, w]", key);
  }
  const Eigen::Quaterniond q(xyzw[3], xyzw[0], xyzw[1], xyzw[2]);
  if (std::abs(q.norm() - 1.0) > 1e-6) {
    section.fail("is not a unit quaternion", key);
  }
  return q;
}

}  // namespace

WrapperConfig parseWrapperConfig(const std::string& yaml_text, const std::string& source,
                                 const std::string& controller_name) {
  YAML::Node root;
  try {
    root = YAML::Load(yaml_text);
  } catch (const YAML::Exception& error) {
    throw std::runtime_error(source + ": not valid YAML: " + error.what());
  }
  if (!root || !root.IsMap() || root.size() == 0) {
    throw std::runtime_error(source + ": expected '<controller_name>: ros__parameters: ...'");
  }
  WrapperConfig config;
  if (controller_name.empty()) {
    if (root.size() != 1) {
      throw std::runtime_error(source + ": holds several controllers; name the one to use");
    }
    config.name = root.begin()->first.as<std::string>();
  } else {
    config.name = controller_name;
    if (!root[controller_name]) {
      throw std::runtime_error(source + ": no controller named '" + controller_name + "'");
    }
  }
  const YAML::Node parameters_node = root[config.name]["ros__parameters"];
  if (!parameters_node) {
    throw std::runtime_error(source + ": " + config.name + " has no 'ros__parameters' section");
  }
  Section parameters(parameters_node, config.name + ".ros__parameters", source);

  config.plugin = parameters.required("plugin");
  config.plugin_parameters = readPluginParameters(parameters, source);
  config.robot = parameters.required("robot");
  const model::RobotDescription robot = model::loadRobotDescription(config.robot);
  config.joints = parameters.value<std::vector<std::string>>("joints", robot.joints);
  config.base_frame = parameters.value<std::string>("base_frame", robot.base_frame);
  config.tip_frame = parameters.value<std::string>("tip_frame", robot.tcp_frame);
  const int dof = static_cast<int>(config.joints.size());
  if (dof < 1 || dof > kMaxDof) {
    // Every per-joint vector downstream has inline storage for kMaxDof entries.
    parameters.fail(
        "has " + std::to_string(dof) + " entries, expected 1 to " + std::to_string(kMaxDof),
        "joints");
  }
  config.dof = dof;

  config.command_timeout_s = parameters.value("command_timeout_s", config.command_timeout_s);
  const auto behavior = parameters.value<std::string>("timeout_behavior", "hold");
  if (behavior != "hold" && behavior != "reanchor") {
    parameters.fail("must be 'hold' or 'reanchor'", "timeout_behavior");
  }
  config.timeout_behavior =
      behavior == "hold" ? TimeoutBehavior::kHold : TimeoutBehavior::kReanchor;

  Section validation = parameters.section("validation");
  ValidationConfig& limits = config.validation;
  limits.quaternion_tolerance =
      validation.value("quaternion_tolerance", limits.quaternion_tolerance);
  limits.max_position_jump_m = validation.value("max_position_jump_m", limits.max_position_jump_m);
  limits.max_orientation_jump_rad =
      validation.value("max_orientation_jump_rad", limits.max_orientation_jump_rad);
  limits.max_joint_jump_rad = validation.value("max_joint_jump_rad", limits.max_joint_jump_rad);
  validation.rejectUnknownKeys();

  Section compensation = parameters.section("compensation");
  config.gravity_compensation = compensation.value("gravity", true);
  Section payload = compensation.section("payload");
  config.payload_compensation = payload.value("enabled", false);
  config.payload.mass_kg = payload.value("mass_kg", 0.0);
  const auto com = payload.value<std::vector<double>>("com_m", {0.0, 0.0, 0.0});
  if (com.size() != 3 || config.payload.mass_kg < 0.0) {
    payload.fail("needs mass_kg >= 0 and com_m [x, y, z] in the tip frame");
  }
  config.payload.com_in_tip = Eigen::Vector3d(com[0], com[1], com[2]);
  payload.rejectUnknownKeys();

  Section friction = compensation.section("friction");
  const auto friction_model = friction.value<std::string>("model", "none");
  FrictionConfig& f = config.friction;
  if (friction_model == "sigmoid") {
    f.model = FrictionModel::kSigmoid;
    const bool from_robot = robot.friction && robot.joints == config.joints;
    f.phi1 =
        friction.perJoint("phi1", dof, from_robot ? robot.friction->phi1 : std::vector<double>{});
    f.phi2 =
        friction.perJoint("phi2", dof, from_robot ? robot.friction->phi2 : std::vector<double>{});
    f.phi3 =
        friction.perJoint("phi3", dof, from_robot ? robot.friction->phi3 : std::vector<double>{});
    if (f.phi1.empty() || f.phi2.empty() || f.phi3.empty()) {
      friction.fail("model sigmoid needs phi1, phi2, phi3 (robot.yaml has none for " + robot.name +
                    ")");
    }
  } else if (friction_model == "viscous_coulomb") {
    f.model = FrictionModel::kViscousCoulomb;
    f.viscous = friction.perJoint("viscous", dof, std::vector<double>(dof, 0.0));
    f.coulomb = friction.perJoint("coulomb", dof, std::vector<double>(dof, 0.0));
    f.smoothing_velocity = friction.value("smoothing_velocity", f.smoothing_velocity);
    if (!(f.smoothing_velocity > 0.0)) {
      friction.fail("must be > 0", "smoothing_velocity");
    }
  } else if (friction_model != "none") {
    friction.fail("must be none, sigmoid or viscous_coulomb", "model");
  }
  friction.rejectUnknownKeys();
  compensation.rejectUnknownKeys();

  Section soft = parameters.section("soft_limits");
  config.soft_limits.enabled = soft.value("enabled", true);
  config.soft_limits.margin = soft.perJoint("margin_rad", dof, std::vector<double>(dof, 0.1));
  config.soft_limits.stiffness = soft.perJoint("stiffness", dof, std::vector<double>(dof, 100.0));
  config.soft_limits.damping = soft.perJoint("damping", dof, std::vector<double>(dof, 5.0));
  soft.rejectUnknownKeys();

  config.filter_alpha = parameters.value("filter_alpha", 1.0);
  if (!(config.filter_alpha > 0.0 && config.filter_alpha <= 1.0)) {
    parameters.fail("must be in (0, 1]", "filter_alpha");
  }
  config.torque_rate_limit =
      parameters.perJoint("torque_rate_limit_nm_per_s", dof, std::vector<double>(dof, 1000.0));
  config.effort_limit = parameters.perJoint("effort_limit_nm", dof, {});
  config.fault_damping = parameters.perJoint("fault_damping", dof, std::vector<double>(dof, 5.0));
  const std::pair<const char*, const std::vector<double>*> non_negative[] = {
      {"torque_rate_limit_nm_per_s", &config.torque_rate_limit},
      {"fault_damping", &config.fault_damping},
      {"soft_limits.margin_rad", &config.soft_limits.margin},
      {"soft_limits.stiffness", &config.soft_limits.stiffness},
      {"soft_limits.damping", &config.soft_limits.damping}};
  for (const auto& [key, list] : non_negative) {
    if (std::any_of(list->begin(), list->end(), [](double v) { return !(v >= 0.0); })) {
      parameters.fail("must be >= 0", key);
    }
  }

  Section initial = parameters.section("initial");
  JointCommand& joint = config.initial_joint;
  joint = JointCommand::zero(dof);
  const auto joint_stiffness = initial.perJoint("stiffness", dof, std::vector<double>(dof, 100.0));
  const auto joint_damping = initial.perJoint("damping", dof, std::vector<double>(dof, 10.0));
  for (int i = 0; i < dof; ++i) {
    joint.stiffness[i] = joint_stiffness[i];
    joint.damping[i] = joint_damping[i];
  }
  CartesianCommand& cartesian = config.initial_cartesian;
  cartesian = CartesianCommand::zero(dof);
  cartesian.stiffness_translational =
      initial.block("stiffness_translational", 500.0 * Eigen::Matrix3d::Identity());
  cartesian.stiffness_rotational =
      initial.block("stiffness_rotational", 30.0 * Eigen::Matrix3d::Identity());
  cartesian.damping_translational =
      initial.block("damping_translational", 45.0 * Eigen::Matrix3d::Identity());
  cartesian.damping_rotational =
      initial.block("damping_rotational", 3.0 * Eigen::Matrix3d::Identity());
  const auto mode = initial.value<std::string>("damping_mode", "ratio");
  if (mode != "ratio" && mode != "absolute") {
    initial.fail("must be 'ratio' or 'absolute'", "damping_mode");
  }
  cartesian.damping_mode = mode == "ratio" ? DampingMode::kRatio : DampingMode::kAbsolute;
  const auto ratio = initial.perJoint("damping_ratio", 6, std::vector<double>(6, 1.0));
  cartesian.damping_ratio = Eigen::Map<const Vector6d>(ratio.data());
  cartesian.task_frame = readQuaternion(initial, "task_frame");
  const auto ns_stiffness =
      initial.perJoint("nullspace_stiffness", dof, std::vector<double>(dof, 2.0));
  const auto ns_damping = initial.perJoint("nullspace_damping", dof, std::vector<double>(dof, 0.5));
  for (int i = 0; i < dof; ++i) {
    cartesian.nullspace_stiffness[i] = ns_stiffness[i];
    cartesian.nullspace_damping[i] = ns_damping[i];
  }
  initial.rejectUnknownKeys();
  parameters.rejectUnknownKeys();
  return config;
}

WrapperConfig loadWrapperConfig(const std::filesystem::path& file,
                                const std::string& controller_name) {
  std::ifstream stream(file);
  if (!stream) {
    throw std::runtime_error("cannot read controller configuration '" + file.string() + "'");
  }
  std::stringstream text;
  text << stream.rdbuf();
  return parseWrapperConfig(text.str(), file.string(), controller_name);
}

}  // namespace comply::pipeline
