#include "comply_mujoco_hardware/mujoco_system.hpp"

#include <algorithm>
#include <cmath>
#include <hardware_interface/types/hardware_interface_type_values.hpp>
#include <limits>
#include <pluginlib/class_list_macros.hpp>
#include <rclcpp/rclcpp.hpp>
#include <stdexcept>

#include "comply/model/robot_description.hpp"
#include "comply_ros2_control/prefix_search.hpp"

namespace comply_mujoco_hardware {
namespace {

namespace hi = hardware_interface;

std::string parameter(const hi::HardwareInfo& info, const std::string& name,
                      const std::string& fallback) {
  const auto found = info.hardware_parameters.find(name);
  return found == info.hardware_parameters.end() ? fallback : found->second;
}

double positiveNumber(const hi::HardwareInfo& info, const std::string& name, double fallback) {
  const std::string text = parameter(info, name, "");
  if (text.empty()) {
    return fallback;
  }
  std::size_t used = 0;
  double value = std::numeric_limits<double>::quiet_NaN();
  try {
    value = std::stod(text, &used);
  } catch (const std::exception&) {
  }
  if (used != text.size() || !(value > 0.0) || !std::isfinite(value)) {
    throw std::invalid_argument("hardware parameter " + name + ": '" + text +
                                "' is not a positive number");
  }
  return value;
}

bool hasInterface(const std::vector<hi::InterfaceInfo>& interfaces, const std::string& name) {
  return std::any_of(interfaces.begin(), interfaces.end(),
                     [&name](const hi::InterfaceInfo& i) { return i.name == name; });
}

}  // namespace

void MujocoSystem::checkInterfaces() const {
  for (const auto& joint : info_.joints) {
    if (joint.command_interfaces.size() != 1 || joint.command_interfaces[0].name != "effort") {
      throw std::invalid_argument("joint '" + joint.name +
                                  "': exactly one command interface, effort, is simulated");
    }
    for (const char* kind : {"position", "velocity", "effort"}) {
      if (!hasInterface(joint.state_interfaces, kind)) {
        throw std::invalid_argument("joint '" + joint.name + "' lacks the " + kind +
                                    " state interface");
      }
    }
  }
}

void MujocoSystem::mapJoints(const std::vector<std::string>& robot_joints) {
  if (info_.joints.size() != robot_joints.size()) {
    throw std::invalid_argument("the <ros2_control> block lists " +
                                std::to_string(info_.joints.size()) + " joints; the robot has " +
                                std::to_string(robot_joints.size()) + ", all of which are needed");
  }
  for (const auto& joint : info_.joints) {
    const auto found = std::find(robot_joints.begin(), robot_joints.end(), joint.name);
    if (found == robot_joints.end()) {
      throw std::invalid_argument("joint '" + joint.name + "' is not a joint of the robot");
    }
    plant_index_.push_back(static_cast<std::size_t>(found - robot_joints.begin()));
  }
}

MujocoSystem::CallbackReturn MujocoSystem::on_init(const hi::HardwareInfo& info) {
  if (SystemInterface::on_init(info) != CallbackReturn::SUCCESS) {
    return CallbackReturn::ERROR;
  }
  const auto logger = rclcpp::get_logger(info.name);
  try {
    const std::string robot_name = parameter(info, "robot", "");
    if (robot_name.empty()) {
      throw std::invalid_argument(
          "hardware parameter robot (a comply robot name or folder) is "
          "missing");
    }
    const auto robot =
        comply::model::loadRobotDescription(comply_ros2_control::robotInPrefix(robot_name));
    checkInterfaces();
    mapJoints(robot.joints);
    comply::sim::PlantOptions options;
    options.control_period_s = positiveNumber(info, "period_s", 0.001);
    options.substeps = static_cast<int>(positiveNumber(info, "substeps", 1.0));
    plant_ = std::make_unique<comply::sim::SimulatedRobot>(robot, options);
    plant_->setJointPositions(robot.home);
    RCLCPP_INFO(logger, "MuJoCo plant of %s: %zu joints, %.4f s per period, %d substeps",
                robot.name.c_str(), robot.joints.size(), options.control_period_s,
                options.substeps);
  } catch (const std::exception& error) {
    RCLCPP_ERROR(logger, "%s", error.what());
    return CallbackReturn::ERROR;
  }
  const std::size_t dof = info_.joints.size();
  measured_ = comply::JointState::zero(static_cast<int>(dof));
  plant_torque_.assign(dof, 0.0);
  position_.assign(dof, 0.0);
  velocity_.assign(dof, 0.0);
  effort_.assign(dof, 0.0);
  // NaN until a controller writes: the plant keeps holding the start pose meanwhile.
  command_.assign(dof, std::numeric_limits<double>::quiet_NaN());
  read(rclcpp::Time(0), rclcpp::Duration(0, 0));
  return CallbackReturn::SUCCESS;
}

std::vector<hi::StateInterface> MujocoSystem::export_state_interfaces() {
  std::vector<hi::StateInterface> interfaces;
  for (std::size_t i = 0; i < info_.joints.size(); ++i) {
    const std::string& joint = info_.joints[i].name;
    interfaces.emplace_back(joint, hi::HW_IF_POSITION, &position_[i]);
    interfaces.emplace_back(joint, hi::HW_IF_VELOCITY, &velocity_[i]);
    interfaces.emplace_back(joint, hi::HW_IF_EFFORT, &effort_[i]);
  }
  return interfaces;
}

std::vector<hi::CommandInterface> MujocoSystem::export_command_interfaces() {
  std::vector<hi::CommandInterface> interfaces;
  for (std::size_t i = 0; i < info_.joints.size(); ++i) {
    interfaces.emplace_back(info_.joints[i].name, hi::HW_IF_EFFORT, &command_[i]);
  }
  return interfaces;
}

hi::return_type MujocoSystem::read(const rclcpp::Time&, const rclcpp::Duration&) {
  if (!plant_->read(measured_)) {
    return hi::return_type::ERROR;
  }
  for (std::size_t i = 0; i < plant_index_.size(); ++i) {
    const auto joint = static_cast<Eigen::Index>(plant_index_[i]);
    position_[i] = measured_.position[joint];
    velocity_[i] = measured_.velocity[joint];
    effort_[i] = measured_.effort[joint];
  }
  return hi::return_type::OK;
}

hi::return_type MujocoSystem::write(const rclcpp::Time&, const rclcpp::Duration&) {
  bool all_finite = true;
  for (std::size_t i = 0; i < plant_index_.size(); ++i) {
    plant_torque_[plant_index_[i]] = command_[i];
    all_finite = all_finite && std::isfinite(command_[i]);
  }
  // A non-finite effort is refused by the plant, which keeps its previous torque (the start
  // pose's holding torque before any controller wrote).
  if (all_finite) {
    plant_->write(plant_torque_);
  }
  plant_->step();
  return hi::return_type::OK;
}

}  // namespace comply_mujoco_hardware

PLUGINLIB_EXPORT_CLASS(comply_mujoco_hardware::MujocoSystem, hardware_interface::SystemInterface)
