// The two controllers ros2_control loads by name (comply_ros2_control.xml).
#include <pluginlib/class_list_macros.hpp>

#include "comply_ros2_control/comply_controller.hpp"

PLUGINLIB_EXPORT_CLASS(comply_ros2_control::JointController,
                       controller_interface::ControllerInterface)
PLUGINLIB_EXPORT_CLASS(comply_ros2_control::CartesianController,
                       controller_interface::ControllerInterface)
