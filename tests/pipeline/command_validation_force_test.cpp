// The pose-jump check along force axes: the target's components along the axes that stay force
// axes with a command are left out (its own selection, else the one in force; its task frame,
// else the one in force), translational and rotational; an axis turned off is checked in full;
// with two selections in force the larger jump counts.

#include <gtest/gtest.h>

#include <array>
#include <cmath>

#include "comply/pipeline/command_validation.hpp"

namespace comply::pipeline::test {
namespace {

constexpr int kDof = 7;

MeasuredPose measured() {
  MeasuredPose pose;
  pose.tcp_position = {0.4, 0.1, 0.5};
  pose.tcp_orientation = Eigen::Quaterniond(Eigen::AngleAxisd(0.3, Eigen::Vector3d::UnitY()));
  pose.valid = true;
  return pose;
}

/// A position command `offset` from the measured TCP, turned `angle` about `axis` from it.
CartesianCommand target(const Eigen::Vector3d& offset, double angle = 0.0,
                        const Eigen::Vector3d& axis = Eigen::Vector3d::UnitZ()) {
  CartesianCommand command = CartesianCommand::zero(kDof);
  command.stamp_s = 2.0;
  command.fields = CommandField::kPosition;
  command.position = measured().tcp_position + offset;
  command.orientation =
      Eigen::Quaterniond(Eigen::AngleAxisd(angle, axis.normalized())) * measured().tcp_orientation;
  return command;
}

Verdict check(CartesianCommand command, std::span<const ForceSelection> in_force) {
  return validateCommand(command, ValidationConfig{}, kDof, measured(), 1.0, in_force);
}

TEST(ForceAxisValidation, TheInForceSelectionLeavesItsAxesOut) {
  const std::array<ForceSelection, 1> z{ForceSelection{Vector6d::Unit(2), {}}};
  EXPECT_TRUE(check(target({0.0, 0.0, 0.5}), z).accepted);
  const Verdict sideways = check(target({0.0, 0.12, 0.5}), z);
  EXPECT_EQ(sideways.reason, RejectionReason::kPoseJump);
  EXPECT_NE(sideways.message.find("target is 0.12 m / "), std::string::npos) << sideways.message;
  EXPECT_NE(sideways.message.find("measured pose off the force axes (limits"), std::string::npos)
      << sideways.message;
  EXPECT_EQ(check(target({0.0, 0.0, 0.5}), {}).reason, RejectionReason::kPoseJump);
}

TEST(ForceAxisValidation, InTheTaskFrameAndAboutItsAxes) {
  // Task frame turned 90 degrees about base x: task y is base z, task rz is about base -y.
  ForceSelection selection;
  selection.axes[1] = 1.0;
  selection.axes[5] = 1.0;
  selection.task_frame =
      Eigen::Quaterniond(Eigen::AngleAxisd(M_PI / 2.0, Eigen::Vector3d::UnitX()));
  const std::array<ForceSelection, 1> in_force{selection};
  EXPECT_TRUE(check(target({0.0, 0.0, 0.4}, 1.2, -Eigen::Vector3d::UnitY()), in_force).accepted);
  EXPECT_EQ(check(target({0.0, 0.4, 0.0}), in_force).reason, RejectionReason::kPoseJump);
  EXPECT_EQ(check(target(Eigen::Vector3d::Zero(), 1.2, Eigen::Vector3d::UnitZ()), in_force).reason,
            RejectionReason::kPoseJump);
}

TEST(ForceAxisValidation, TheCommandsOwnSelectionAndFrameCount) {
  const std::array<ForceSelection, 1> z{ForceSelection{Vector6d::Unit(2), {}}};
  // Turning z off: checked in full.
  CartesianCommand off = target({0.0, 0.0, 0.5});
  off.fields = off.fields | CommandField::kForce;
  EXPECT_EQ(check(off, z).reason, RejectionReason::kPoseJump);
  // Selecting x instead: x left out, z checked.
  CartesianCommand along_x = target({0.5, 0.0, 0.0});
  along_x.fields = along_x.fields | CommandField::kForce;
  along_x.force_axes[0] = 1.0;
  EXPECT_TRUE(check(along_x, z).accepted);
  along_x.position.z() += 0.5;
  EXPECT_EQ(check(along_x, z).reason, RejectionReason::kPoseJump);
  // The command's frame: in force z, its own task frame turns z onto base x.
  CartesianCommand turned = target({0.5, 0.0, 0.0});
  turned.fields = turned.fields | CommandField::kTaskFrame;
  turned.task_frame = Eigen::Quaterniond(Eigen::AngleAxisd(M_PI / 2.0, Eigen::Vector3d::UnitY()));
  EXPECT_TRUE(check(turned, z).accepted);
}

TEST(ForceAxisValidation, WithTwoSelectionsInForceTheLargerJumpCounts) {
  const std::array<ForceSelection, 2> both{ForceSelection{Vector6d::Unit(2), {}},
                                           ForceSelection{Vector6d::Zero(), {}}};
  EXPECT_EQ(check(target({0.0, 0.0, 0.5}), both).reason, RejectionReason::kPoseJump);
  const std::array<ForceSelection, 2> agree{ForceSelection{Vector6d::Unit(2), {}},
                                            ForceSelection{Vector6d::Unit(2), {}}};
  EXPECT_TRUE(check(target({0.0, 0.0, 0.5}), agree).accepted);
}

TEST(ForceAxisValidation, ValidateAndMergeReadsTheMergedCommandsSelection) {
  CartesianCommand merged = CartesianCommand::zero(kDof);
  merged.force_axes[2] = 1.0;
  const CartesianCommand up = target({0.0, 0.0, 0.5});
  EXPECT_TRUE(validateAndMerge(up, ValidationConfig{}, kDof, measured(), merged).accepted);
  EXPECT_EQ(merged.position, up.position);
  merged.force_axes[2] = 0.0;
  CartesianCommand again = up;
  again.stamp_s = 3.0;
  EXPECT_EQ(validateAndMerge(again, ValidationConfig{}, kDof, measured(), merged).reason,
            RejectionReason::kPoseJump);
}

}  // namespace
}  // namespace comply::pipeline::test
