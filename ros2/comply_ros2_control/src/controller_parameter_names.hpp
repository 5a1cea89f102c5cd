#pragma once
// The controller's own parameters, beside comply's options (comply_parameters.hpp lists them as
// ROS-side, so comply's parser never sees them). Private to the package's sources.

#include <cstddef>

namespace comply_ros2_control::parameter_names {

inline constexpr const char* kStateRate = "state_publish_rate_hz";
inline constexpr const char* kDiagnosticsRate = "diagnostics_publish_rate_hz";
inline constexpr const char* kRobotDescription = "robot_description";
// The wrist force/torque sensor's state interfaces: "<name>/force.x" ... "<name>/torque.z" (the
// ros2_control ForceTorqueSensor names), or six full names; its frame: tcp (the sensor's axes,
// aligned with the TCP) or base.
inline constexpr const char* kSensorName = "force_torque_sensor.name";
inline constexpr const char* kSensorInterfaces = "force_torque_sensor.interface_names";
inline constexpr const char* kSensorFrame = "force_torque_sensor.frame";
inline constexpr const char* kRecord = "record";      ///< an MCAP file to record to ("": none)
inline constexpr const char* kFoxglove = "foxglove";  ///< the live view's [ADDRESS:]PORT ("": none)
inline constexpr std::size_t kCommandDepth = 1000;  ///< commands waiting for the executor, at most

}  // namespace comply_ros2_control::parameter_names
