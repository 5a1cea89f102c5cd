// A URDF's links placed from joint positions (see robot_frames.hpp).

#include "comply/viewer/robot_frames.hpp"

#include <urdf_parser/urdf_parser.h>

#include <algorithm>
#include <stdexcept>

namespace comply::viewer {
namespace {

Eigen::Isometry3d toIsometry(const urdf::Pose& pose) {
  Eigen::Isometry3d result = Eigen::Isometry3d::Identity();
  result.translation() = Eigen::Vector3d(pose.position.x, pose.position.y, pose.position.z);
  result.linear() =
      Eigen::Quaterniond(pose.rotation.w, pose.rotation.x, pose.rotation.y, pose.rotation.z)
          .normalized()
          .toRotationMatrix();
  return result;
}

}  // namespace

RobotFrames::RobotFrames(const std::string& urdf_xml, const std::vector<std::string>& joints) {
  const urdf::ModelInterfaceSharedPtr model = urdf::parseURDF(urdf_xml);
  if (!model) {
    throw std::invalid_argument("the robot's URDF does not parse");
  }
  root_ = model->getRoot() ? model->getRoot()->name : std::string();
  for (const std::string& name : joints) {
    if (!model->getJoint(name)) {
      throw std::invalid_argument("joint \"" + name + "\" is not in the robot's URDF");
    }
  }
  // urdfdom keeps joints in a map by name: the transforms come out in name order.
  for (const auto& [name, joint] : model->joints_) {
    Motion motion = Motion::kFixed;
    if (joint->type == urdf::Joint::REVOLUTE || joint->type == urdf::Joint::CONTINUOUS) {
      motion = Motion::kRevolute;
    } else if (joint->type == urdf::Joint::PRISMATIC) {
      motion = Motion::kPrismatic;
    }
    const auto listed = std::find(joints.begin(), joints.end(), name);
    const int index =
        listed == joints.end() ? -1 : static_cast<int>(std::distance(joints.begin(), listed));
    Eigen::Vector3d axis(joint->axis.x, joint->axis.y, joint->axis.z);
    if (motion != Motion::kFixed) {
      if (axis.norm() == 0.0) {
        throw std::invalid_argument("joint \"" + name + "\" of the robot's URDF has no axis");
      }
      axis.normalize();
    }
    joints_.push_back({toIsometry(joint->parent_to_joint_origin_transform), axis, motion, index});
    transforms_.push_back({joint->parent_link_name, joint->child_link_name, joints_.back().origin});
  }
}

void RobotFrames::update(std::span<const double> position) {
  for (std::size_t i = 0; i < joints_.size(); ++i) {
    const Joint& joint = joints_[i];
    const double q = joint.position_index >= 0 &&
                             static_cast<std::size_t>(joint.position_index) < position.size()
                         ? position[static_cast<std::size_t>(joint.position_index)]
                         : 0.0;
    Eigen::Isometry3d motion = Eigen::Isometry3d::Identity();
    if (joint.motion == Motion::kRevolute) {
      motion.linear() = Eigen::AngleAxisd(q, joint.axis).toRotationMatrix();
    } else if (joint.motion == Motion::kPrismatic) {
      motion.translation() = q * joint.axis;
    }
    transforms_[i].parent_to_child = joint.origin * motion;
  }
}

}  // namespace comply::viewer
