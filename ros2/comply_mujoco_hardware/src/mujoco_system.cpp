#include "comply_mujoco_hardware/mujoco_system.hpp"

#include <algorithm>
#include <cmath>
#include <hardware_interface/types/hardware_interface_type_values.hpp>
#include <iterator>
#include <limits>
#include <optional>
#include <pluginlib/class_list_macros.hpp>
#include <rclcpp/rclcpp.hpp>
#include <span>
#include <sstream>
#include <stdexcept>

#include "comply/core/number_text.hpp"
#include "comply/model/robot_description.hpp"
#include "comply_ros2_control/command_interfaces.hpp"
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
  const std::optional<double> value = comply::finiteNumber(text);
  if (!value || !(*value > 0.0)) {
    throw std::invalid_argument("hardware parameter " + name + ": '" + text +
                                "' is not a positive number");
  }
  return *value;
}

constexpr const char* kWrenchAxes[] = {"force.x",  "force.y",  "force.z",
                                       "torque.x", "torque.y", "torque.z"};

/// Six numbers separated by spaces (force x y z [N], torque x y z [N m]); zero when not given.
comply::Vector6d sixNumbers(const hi::HardwareInfo& info, const std::string& name) {
  const std::string text = parameter(info, name, "");
  comply::Vector6d values = comply::Vector6d::Zero();
  if (text.empty()) {
    return values;
  }
  std::istringstream words(text);
  std::vector<std::string> numbers{std::istream_iterator<std::string>(words), {}};
  for (std::size_t k = 0; k < numbers.size() && k < 6; ++k) {
    const std::optional<double> value = comply::finiteNumber(numbers[k]);
    values[static_cast<Eigen::Index>(k)] = value.value_or(std::nan(""));
  }
  if (numbers.size() != 6 || !values.allFinite()) {
    throw std::invalid_argument("hardware parameter " + name + ": '" + text +
                                "' is not six finite numbers (force x y z, torque x y z)");
  }
  return values;
}

bool hasInterface(const std::vector<hi::InterfaceInfo>& interfaces, const std::string& name) {
  return std::any_of(interfaces.begin(), interfaces.end(),
                     [&name](const hi::InterfaceInfo& i) { return i.name == name; });
}

}  // namespace

void MujocoSystem::checkInterfaces() const {
  const std::string wanted = comply_ros2_control::commandKindsOf(actuation_);
  for (const auto& joint : info_.joints) {
    std::string listed;
    for (const auto& interface : joint.command_interfaces) {
      listed += (listed.empty() ? "" : ", ") + interface.name;
    }
    if (listed != wanted) {
      throw std::invalid_argument("joint '" + joint.name + "': a plant actuated by " +
                                  std::string(comply::toString(actuation_)) +
                                  " takes the command interfaces " + wanted +
                                  " (in this order), not " + (listed.empty() ? "none" : listed) +
                                  " (hardware parameter actuation; docs/ros2.md)");
    }
    for (const char* kind : {"position", "velocity", "effort"}) {
      if (!hasInterface(joint.state_interfaces, kind)) {
        throw std::invalid_argument("joint '" + joint.name + "' lacks the " + kind +
                                    " state interface");
      }
    }
  }
  for (const auto& sensor : info_.sensors) {
    for (const char* axis : kWrenchAxes) {
      if (!hasInterface(sensor.state_interfaces, axis)) {
        throw std::invalid_argument("sensor '" + sensor.name + "' lacks the " + axis +
                                    " state interface: the plant's wrist sensor exports force.x, "
                                    "force.y, force.z, torque.x, torque.y, torque.z");
      }
    }
  }
  if (info_.sensors.size() > 1) {
    throw std::invalid_argument("the plant has one wrist force/torque sensor; the block lists " +
                                std::to_string(info_.sensors.size()));
  }
}

comply::OutputMode MujocoSystem::actuationOf(const std::string& text) {
  for (const auto& entry : comply::kOutputModeNames) {
    if (entry.name == text) {
      return entry.value;
    }
  }
  throw std::invalid_argument("hardware parameter actuation: '" + text +
                              "' is not torque, joint_pd, position or velocity");
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
    actuation_ = actuationOf(parameter(info, "actuation", "torque"));
    checkInterfaces();
    mapJoints(robot.joints);
    comply::sim::PlantOptions options;
    options.actuation = actuation_;
    options.wrench_sensor_offset = sixNumbers(info, "wrench_sensor_offset");
    options.control_period_s = positiveNumber(info, "period_s", 0.001);
    options.substeps = static_cast<int>(positiveNumber(info, "substeps", 1.0));
    plant_ = std::make_unique<comply::sim::SimulatedRobot>(robot, options);
    robot_dof_ = robot.joints.size();
    plant_->setJointPositions(robot.home);
    RCLCPP_INFO(logger,
                "MuJoCo plant of %s: %zu joints actuated by %s, %.4f s per period, %d substeps%s",
                robot.name.c_str(), robot.joints.size(),
                std::string(comply::toString(actuation_)).c_str(), options.control_period_s,
                options.substeps, info_.sensors.empty() ? "" : ", a wrist force/torque sensor");
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
  fields_ = comply_ros2_control::commandInterfacesOf(actuation_);
  // NaN until a controller writes: the plant keeps holding the start pose meanwhile.
  command_.assign(dof * fields_.size(), std::numeric_limits<double>::quiet_NaN());
  drive_.resize(static_cast<int>(robot_dof_));
  drive_.mode = actuation_;
  wrench_.fill(0.0);
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
  for (const auto& sensor : info_.sensors) {
    for (std::size_t k = 0; k < 6; ++k) {
      interfaces.emplace_back(sensor.name, kWrenchAxes[k], &wrench_[k]);
    }
  }
  return interfaces;
}

std::vector<hi::CommandInterface> MujocoSystem::export_command_interfaces() {
  std::vector<hi::CommandInterface> interfaces;
  for (std::size_t i = 0; i < info_.joints.size(); ++i) {
    for (std::size_t k = 0; k < fields_.size(); ++k) {
      interfaces.emplace_back(info_.joints[i].name, fields_[k].kind,
                              &command_[i * fields_.size() + k]);
    }
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
  if (!info_.sensors.empty()) {
    // The sensor's axes are the TCP's, as a wrist sensor's are: the plant reads in the base.
    comply::Vector6d in_base;
    if (plant_->readWrench(in_base)) {
      const Eigen::Matrix3d base_to_tcp = plant_->tcpPose().linear().transpose();
      Eigen::Map<comply::Vector6d> wrench(wrench_.data());
      wrench.head<3>() = base_to_tcp * in_base.head<3>();
      wrench.tail<3>() = base_to_tcp * in_base.tail<3>();
    }
  }
  return hi::return_type::OK;
}

hi::return_type MujocoSystem::write(const rclcpp::Time&, const rclcpp::Duration&) {
  const std::size_t fields = fields_.size();
  bool all_finite = true;
  bool torque_finite = true;
  for (std::size_t i = 0; i < plant_index_.size(); ++i) {
    const auto joint = static_cast<Eigen::Index>(plant_index_[i]);
    for (std::size_t k = 0; k < fields; ++k) {
      const double value = command_[i * fields + k];
      (drive_.*fields_[k].field)[joint] = value;
      all_finite = all_finite && std::isfinite(value);
    }
    torque_finite = torque_finite && std::isfinite(drive_.effort[joint]);
  }
  // A non-finite command is refused by the plant, which keeps its previous one (the start pose's
  // hold before any controller wrote). A joint_pd drive takes a torque alone as well (kp = kd =
  // 0): what a controller in torque mode claims of it.
  if (all_finite) {
    plant_->writeCommand(drive_);
  } else if (actuation_ == comply::OutputMode::kJointPd && torque_finite) {
    plant_->write(std::span<const double>(drive_.effort.data(), robot_dof_));
  }
  plant_->step();
  return hi::return_type::OK;
}

}  // namespace comply_mujoco_hardware

PLUGINLIB_EXPORT_CLASS(comply_mujoco_hardware::MujocoSystem, hardware_interface::SystemInterface)
