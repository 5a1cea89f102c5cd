#pragma once
// Measured joint state as read from hardware (real or simulated).

#include <Eigen/Geometry>
#include <cstdint>

#include "comply/core/capacity.hpp"

namespace comply {

struct JointState {
  JointVector position;  ///< rad | m
  JointVector velocity;  ///< rad/s | m/s
  JointVector effort;    ///< measured torque, N m | N
  /// A wrist force/torque sensor's reading, where the hardware has one and it was valid this cycle
  /// (HardwareInterface::readWrench): the wrench on the tool at the TCP as the sensor reads it,
  /// base frame, force first [N, N m].
  Eigen::Matrix<double, 6, 1> wrench = Eigen::Matrix<double, 6, 1>::Zero();
  bool wrench_valid = false;
  /// `wrench` is in the TCP frame (the sensor's own axes, as a ros2_control force-torque sensor
  /// reports it) instead of the base frame; the cycle turns it with the measured TCP.
  bool wrench_in_tcp = false;
  /// The driver's sample counter, where it has one (HardwareInterface::readSequence): it advances
  /// with every new sample, so a stream that repeats itself is caught whatever the arm does.
  std::uint64_t sequence = 0;
  bool sequence_valid = false;
  /// The robot stopped itself and takes no command (a protective or an emergency stop, its
  /// control program ended, the link to it lost): why, in the driver's words; nullptr while it
  /// runs (HardwareInterface::robotStop). The cycle enters FAULT naming it, and no reset leaves
  /// FAULT while it is set.
  const char* robot_stop = nullptr;

  /// `dof` entries each, position and velocity finite: a state a cycle can run on (the effort
  /// may be NaN: an arm without torque sensing).
  [[nodiscard]] bool usable(int dof) const noexcept {
    return position.size() == dof && velocity.size() == dof && effort.size() == dof &&
           position.allFinite() && velocity.allFinite();
  }

  static JointState zero(int dof) {
    JointState state;
    state.position.setZero(dof);
    state.velocity.setZero(dof);
    state.effort.setZero(dof);
    return state;
  }
};

/// The measured configuration a controller last saw: joint positions and the TCP pose in the base
/// frame. Command validation compares targets with it; references are seeded from it.
struct MeasuredPose {
  JointVector position;                                                 ///< q [rad | m]
  Eigen::Vector3d tcp_position = Eigen::Vector3d::Zero();               ///< base frame [m]
  Eigen::Quaterniond tcp_orientation = Eigen::Quaterniond::Identity();  ///< base frame
  bool valid = false;  ///< false until the controller has measured anything
  /// The controller's clock at that cycle [s since activation]: where the intake places a
  /// chunk's waypoints on the cycle's time.
  double time_s = 0.0;
  /// [s] the period that cycle ran at (1 ms until one ran): what gains are checked against.
  double period_s = 0.001;
};

}  // namespace comply
