#pragma once
// comply's MuJoCo plant (sim::SimulatedRobot) as ros2_control hardware: what Gazebo or a MuJoCo
// bridge is for the peers' stacks, with the same plant `comply sim` runs.
//
//   <hardware>
//     <plugin>comply_mujoco_hardware/MujocoSystem</plugin>
//     <param name="robot">fr3</param>           comply robot name or folder (required)
//     <param name="period_s">0.001</param>      simulated time per write() [s]; match update_rate
//     <param name="substeps">1</param>          physics steps per period
//   </hardware>
// Each <joint> claims an `effort` command interface and `position`, `velocity`, `effort` state
// interfaces, and must be a joint of the robot. The arm starts at the robot's home pose, held
// there (as by brakes) until a controller writes a finite effort; each write() then advances the
// plant by period_s, so the simulation runs in real time at the controller manager's rate.

#include <hardware_interface/system_interface.hpp>
#include <memory>
#include <string>
#include <vector>

#include "comply/core/state.hpp"
#include "comply/sim/simulated_robot.hpp"

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

  std::unique_ptr<comply::sim::SimulatedRobot> plant_;
  std::vector<std::size_t> plant_index_;  // per <joint> of the URDF: its index in the plant
  comply::JointState measured_;
  std::vector<double> plant_torque_;
  std::vector<double> position_, velocity_, effort_, command_;
};

}  // namespace comply_mujoco_hardware
