// Completing a controller configuration for its robot: what the file leaves to the robot
// (joints, frames, friction parameters) and what needs the number of joints (per-joint lists,
// the initial commands).

#include <nlohmann/json.hpp>

#include "comply/core/input_error.hpp"
#include "comply/pipeline/config.hpp"
#include "comply/schema/json.hpp"

namespace comply::pipeline {
namespace {

std::string keyOf(const WrapperConfig& config, const std::string& key) {
  return config.name + ".ros__parameters." + key;
}

/// One value for every joint, or one per joint; empty stays empty (no value given).
void expand(std::vector<double>& list, int dof, const WrapperConfig& config, const std::string& key,
            const std::string& source) {
  if (list.size() == 1) {
    list.assign(static_cast<std::size_t>(dof), list.front());
  } else if (!list.empty() && static_cast<int>(list.size()) != dof) {
    throw InputError(
        InputErrc::kWrongSize, source, keyOf(config, key),
        "has " + std::to_string(list.size()) + " values, expected 1 or " + std::to_string(dof));
  }
}

void completeFriction(WrapperConfig& config, const model::RobotDescription& robot,
                      const std::string& source) {
  FrictionConfig& friction = config.friction;
  const int dof = config.dof;
  if (friction.model == FrictionModel::kSigmoid) {
    // robot.yaml's parameters belong to its own joint list; another list needs its own.
    const bool from_robot = robot.friction && robot.joints == config.joints;
    if (from_robot && friction.phi1.empty() && friction.phi2.empty() && friction.phi3.empty()) {
      friction.phi1 = robot.friction->phi1;
      friction.phi2 = robot.friction->phi2;
      friction.phi3 = robot.friction->phi3;
    }
    if (friction.phi1.empty() || friction.phi2.empty() || friction.phi3.empty()) {
      throw InputError(
          InputErrc::kMissingKey, source, keyOf(config, "compensation.friction"),
          "model sigmoid needs phi1, phi2, phi3 (robot.yaml has none for " + robot.name + ")");
    }
  }
  if (friction.model == FrictionModel::kViscousCoulomb) {
    for (std::vector<double>* list : {&friction.viscous, &friction.coulomb}) {
      if (list->empty()) {
        list->assign(static_cast<std::size_t>(dof), 0.0);
      }
    }
  }
  expand(friction.phi1, dof, config, "compensation.friction.phi1", source);
  expand(friction.phi2, dof, config, "compensation.friction.phi2", source);
  expand(friction.phi3, dof, config, "compensation.friction.phi3", source);
  expand(friction.viscous, dof, config, "compensation.friction.viscous", source);
  expand(friction.coulomb, dof, config, "compensation.friction.coulomb", source);
}

}  // namespace

void completeForRobot(WrapperConfig& config, std::shared_ptr<const model::RobotDescription> robot) {
  const std::string source = config.source.empty() ? config.name : config.source;
  if (config.joints.empty()) {
    config.joints = robot->joints;
  }
  if (config.base_frame.empty()) {
    config.base_frame = robot->base_frame;
  }
  if (config.tip_frame.empty()) {
    config.tip_frame = robot->tcp_frame;
  }
  config.dof = static_cast<int>(config.joints.size());
  const int dof = config.dof;
  expand(config.soft_limits.margin, dof, config, "soft_limits.margin_rad", source);
  expand(config.soft_limits.stiffness, dof, config, "soft_limits.stiffness", source);
  expand(config.soft_limits.damping, dof, config, "soft_limits.damping", source);
  expand(config.torque_rate_limit, dof, config, "torque_rate_limit_nm_per_s", source);
  expand(config.effort_limit, dof, config, "effort_limit_nm", source);
  expand(config.fault_damping, dof, config, "fault_damping", source);
  completeFriction(config, *robot, source);
  const nlohmann::json empty = nlohmann::json::object();
  const schema::InitialCommands initial =
      schema::readInitialCommands(config.initial_block ? *config.initial_block : empty, dof, source,
                                  config.name + ".ros__parameters.initial.");
  config.initial_joint = initial.joint;
  config.initial_cartesian = initial.cartesian;
  config.robot_description = std::move(robot);
}

}  // namespace comply::pipeline
