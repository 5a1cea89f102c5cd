#pragma once
// Every link of a URDF placed from the joint positions, as robot_state_publisher does: one
// transform per URDF joint, parent link to child link (the joint's origin, then its motion about
// or along its axis). A 3D panel that loaded the same URDF draws the arm from these.

#include <Eigen/Geometry>
#include <span>
#include <string>
#include <vector>

namespace comply::viewer {

struct LinkTransform {
  std::string parent;
  std::string child;
  Eigen::Isometry3d parent_to_child = Eigen::Isometry3d::Identity();
};

class RobotFrames {
 public:
  /// `urdf_xml`: the robot's URDF text; `joints`: the controlled joints in the order of the
  /// positions update() takes. A joint not listed stays at 0. Throws std::invalid_argument when
  /// the URDF does not parse or a listed joint is not in it.
  RobotFrames(const std::string& urdf_xml, const std::vector<std::string>& joints);

  /// Places every joint's child at `position` (the controlled joints' order). No allocation.
  void update(std::span<const double> position);
  [[nodiscard]] const std::vector<LinkTransform>& transforms() const noexcept {
    return transforms_;
  }
  [[nodiscard]] const std::string& rootLink() const noexcept { return root_; }

 private:
  enum class Motion { kFixed, kRevolute, kPrismatic };
  struct Joint {
    Eigen::Isometry3d origin;
    Eigen::Vector3d axis;
    Motion motion;
    int position_index;  // in update()'s positions; -1: not controlled
  };
  std::vector<Joint> joints_;
  std::vector<LinkTransform> transforms_;
  std::string root_;
};

}  // namespace comply::viewer
