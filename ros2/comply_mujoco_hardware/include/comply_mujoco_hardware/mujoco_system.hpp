#pragma once
// comply's MuJoCo plant (sim::SimulatedRobot) as ros2_control hardware: what Gazebo or a MuJoCo
// bridge is for the peers' stacks, with the same plant `comply sim` runs.
//
//   <hardware>
//     <plugin>comply_mujoco_hardware/MujocoSystem</plugin>
//     <param name="robot">fr3</param>           comply robot name or folder (required)
//     <param name="period_s">0.001</param>      simulated time per write() [s]; match update_rate
//     <param name="substeps">1</param>          physics steps per period
//     <param name="actuation">torque</param>    what the drives take: torque (default), joint_pd,
//                                               position or velocity (docs/output-modes.md)
//     <param name="wrench_sensor_offset">0 0 0 0 0 0</param>   the wrist sensor's own offset in
//                                               its axes, force then torque [N, N m]: what a
//                                               tare removes (default none)
//   </hardware>
//   <sensor name="tcp_fts_sensor">              optional: the wrist force/torque sensor, its
//     <state_interface name="force.x"/> ...     state interfaces force.x ... torque.z in the
//   </sensor>                                   TCP's axes (the sensor's, aligned with it)
// Each <joint> lists the command interfaces of the actuation (command_interfaces.hpp: effort;
// position, velocity, effort, stiffness, damping; position; velocity), and `position`,
// `velocity`, `effort` state interfaces, and must be a joint of the robot; anything else is
// refused at on_init, naming what the actuation takes. The arm starts at the robot's home pose,
// held there (as by brakes) until a controller writes a finite command; each write() then
// advances the plant by period_s, so the simulation runs in real time at the controller
// manager's rate.

#include <array>
#include <hardware_interface/system_interface.hpp>
#include <memory>
#include <string>
#include <vector>

#include "comply/core/state.hpp"
#include "comply/sim/simulated_robot.hpp"
#include "comply_ros2_control/command_interfaces.hpp"

namespace comply_mujoco_hardware {

class MujocoSystem final : public hardware_interface::SystemInterface {
 public:
  using CallbackReturn = hardware_interface::CallbackReturn;

  CallbackReturn on_init(const hardware_interface::HardwareInfo& info) override;
  std::vector<hardware_interface::StateInterface> export_state_interfaces() override;
  std::vector<hardware_interface::CommandInterface> export_command_interfaces() override;
  hardware_interface::return_type read(const rclcpp::Time& time,
                                       const rclcpp::Duration& period) override;
  hardware_interface::return_type write(const rclcpp::Time& time,
                                        const rclcpp::Duration& period) override;

 private:
  void checkInterfaces() const;
  void mapJoints(const std::vector<std::string>& robot_joints);
  static comply::OutputMode actuationOf(const std::string& text);

  std::unique_ptr<comply::sim::SimulatedRobot> plant_;
  std::vector<std::size_t> plant_index_;  // per <joint> of the URDF: its index in the plant
  comply::JointState measured_;
  std::vector<double> plant_torque_;
  std::vector<double> position_, velocity_, effort_;
  comply::OutputMode actuation_ = comply::OutputMode::kTorque;
  std::vector<comply_ros2_control::CommandInterface> fields_;  // the actuation's, per joint
  std::vector<double> command_;    // joint i, field k at i * fields_.size() + k
  comply::ActuatorCommand drive_;  // the plant's command, in plant joint order
  std::size_t robot_dof_ = 0;
  std::array<double, 6> wrench_{};  // the wrist sensor: force then torque, TCP axes [N, N m]
};

}  // namespace comply_mujoco_hardware
