// A workspace box set by a command, through the wrapper on the FR3 at rest (virtual_walls.hpp,
// workspace_intake.hpp): the law's reference is kept inside it, for commands and for the chunks
// that follow; zeros take it away; it lasts through a FAULT's reset; it joins the controller
// file's walls; a box with a corner not below the other, one the TCP lies far outside of, one
// that leaves no room inside the file's walls, and one in a chunk are refused, the last valid box
// staying in force.

#include <gtest/gtest.h>

#include <limits>
#include <string>

#include "comply/core/input_error.hpp"
#include "comply/pipeline/resolved_controller.hpp"
#include "comply/pipeline/wrapper.hpp"
#include "resting_fr3.hpp"
#include "wrapper_support.hpp"

namespace comply::pipeline::test {
namespace {

class Workspace : public RestingFr3 {
 protected:
  explicit Workspace(const std::string& lines = "frozen_state_timeout_s: 0\n")
      : RestingFr3(lines, 0.0) {}

  /// A command that sets the workspace group alone.
  CartesianCommand box(const Eigen::Vector3d& min, const Eigen::Vector3d& max) {
    CartesianCommand command = CartesianCommand::zero(kFr3Dof);
    command.stamp_s = ++stamp;
    command.fields = CommandField::kWorkspace;
    command.workspace_min = min;
    command.workspace_max = max;
    return command;
  }
  /// The box 2 cm ahead of home along x, 10 cm every other way.
  CartesianCommand boxAhead() {
    return box(home_position - Eigen::Vector3d(0.1, 0.1, 0.1),
               home_position + Eigen::Vector3d(0.02, 0.1, 0.1));
  }
  /// A command moving the reference `dx` along x from home.
  CartesianCommand reach(double dx) {
    CartesianCommand command = CartesianCommand::zero(kFr3Dof);
    command.stamp_s = ++stamp;
    command.fields = CommandField::kPosition;
    command.position = home_position + Eigen::Vector3d(dx, 0.0, 0.0);
    command.orientation = home_orientation;
    return command;
  }
  const VirtualWalls& walls() { return wrapper.controller().walls(); }

  double stamp = 0.0;
};

TEST_F(Workspace, ABoxKeepsTheReferenceInside) {
  EXPECT_FALSE(walls().enabled()) << "no walls in the file: the stage is off";
  ASSERT_TRUE(wrapper.submit(boxAhead()).accepted);
  ASSERT_TRUE(wrapper.submit(reach(0.04)).accepted);
  cycles(2);
  EXPECT_TRUE(walls().enabled());
  EXPECT_TRUE(walls().boxCommanded());
  EXPECT_NEAR(walls().distance(), 0.02, 1e-9) << "the nearest face is 2 cm ahead";
  EXPECT_NEAR(reference().x(), home_position.x() + 0.02, 1e-12);
  EXPECT_NEAR(reference().y(), home_position.y(), 1e-12);
  const auto& in_force = std::get<comply_cartesian_command>(wrapper.controller().commandInForce());
  EXPECT_NEAR(in_force.position[0], home_position.x() + 0.04, 1e-12)
      << "the command in force is as sent; only the law's reference is kept inside";
  EXPECT_GT(wrapper.diagnostics().wall_reference_hits, 0U);
}

TEST_F(Workspace, ZerosTakeTheBoxAway) {
  ASSERT_TRUE(wrapper.submit(boxAhead()).accepted);
  ASSERT_TRUE(wrapper.submit(reach(0.04)).accepted);
  cycles(1);
  ASSERT_TRUE(walls().boxCommanded());
  ASSERT_TRUE(wrapper.submit(box(Eigen::Vector3d::Zero(), Eigen::Vector3d::Zero())).accepted);
  cycles(1);
  EXPECT_FALSE(walls().boxCommanded());
  EXPECT_FALSE(walls().enabled());
  EXPECT_NEAR(reference().x(), home_position.x() + 0.04, 1e-12);
}

TEST_F(Workspace, AChunkAfterItIsKeptInside) {
  ASSERT_TRUE(wrapper.submit(boxAhead()).accepted);
  cycles(1);
  CartesianChunk chunk;
  chunk.stamp_s = ++stamp;
  chunk.fields = CommandField::kPosition;
  for (int k = 1; k <= 6; ++k) {
    ChunkWaypoint<CartesianCommand> waypoint{hostTime() + 0.05 * k,
                                             CartesianCommand::zero(kFr3Dof)};
    waypoint.command.position = home_position + Eigen::Vector3d(0.01 * k, 0.0, 0.0);
    waypoint.command.orientation = home_orientation;
    chunk.waypoints.push_back(waypoint);
  }
  ASSERT_TRUE(wrapper.submitChunk(chunk, hostTime()).accepted);
  double furthest = -std::numeric_limits<double>::infinity();
  for (int i = 0; i < 400; ++i) {
    cycles(1);
    furthest = std::max(furthest, reference().x());
  }
  EXPECT_LE(furthest, home_position.x() + 0.02 + 1e-12);
  EXPECT_GT(furthest, home_position.x() + 0.02 - 1e-6) << "the reference never reached the face";
  // A chunk cannot carry a box: a command sets it.
  CartesianChunk boxed = chunk;
  boxed.stamp_s = ++stamp;
  boxed.fields = CommandField::kPosition | CommandField::kWorkspace;
  for (auto& waypoint : boxed.waypoints) {
    waypoint.time_s += 1.0;
  }
  const Verdict refused = wrapper.submitChunk(boxed, hostTime());
  EXPECT_EQ(refused.reason, RejectionReason::kInvalidChunk);
  EXPECT_NE(refused.message.find("workspace"), std::string::npos) << refused.message;
}

TEST_F(Workspace, ABadBoxIsRefusedAndTheLastStays) {
  ASSERT_TRUE(wrapper.submit(boxAhead()).accepted);
  cycles(1);
  const WallBox before = walls().box();
  // A corner not below the other.
  CartesianCommand flat = boxAhead();
  flat.workspace_max.y() = flat.workspace_min.y();
  Verdict verdict = wrapper.submit(flat);
  EXPECT_EQ(verdict.reason, RejectionReason::kInvalidWorkspace);
  EXPECT_NE(verdict.message.find("workspace_min along y"), std::string::npos) << verdict.message;
  // The TCP 10 cm outside it: a box must hold the arm, not yank it there.
  verdict = wrapper.submit(box(home_position + Eigen::Vector3d(0.1, -0.1, -0.1),
                               home_position + Eigen::Vector3d(0.3, 0.1, 0.1)));
  EXPECT_EQ(verdict.reason, RejectionReason::kInvalidWorkspace);
  EXPECT_NE(verdict.message.find("outside the box"), std::string::npos) << verdict.message;
  // 3 cm outside: within the barrier's braking zone, taken (the reference is pulled in).
  EXPECT_TRUE(wrapper
                  .submit(box(home_position + Eigen::Vector3d(0.03, -0.1, -0.1),
                              home_position + Eigen::Vector3d(0.3, 0.1, 0.1)))
                  .accepted);
  EXPECT_TRUE(wrapper.submit(boxAhead()).accepted);
  cycles(1);
  EXPECT_EQ(walls().box().min, before.min);
  EXPECT_EQ(walls().box().max, before.max);
  EXPECT_EQ(wrapper.diagnostics()
                .rejections[static_cast<std::size_t>(RejectionReason::kInvalidWorkspace)],
            2U);
}

TEST_F(Workspace, ABoxLastsThroughAFaultsReset) {
  ASSERT_TRUE(wrapper.submit(boxAhead()).accepted);
  cycles(1);
  JointState broken = state;
  broken.position[2] = std::numeric_limits<double>::quiet_NaN();
  ASSERT_EQ(wrapper.update(broken, kPeriod, torque.span()), CycleStatus::kFault);
  ASSERT_NE(wrapper.reset(), 0U);
  cycles(1);
  EXPECT_TRUE(walls().boxCommanded()) << "a box is a limit: a reset keeps it";
  ASSERT_TRUE(wrapper.submit(reach(0.04)).accepted);
  cycles(1);
  EXPECT_NEAR(reference().x(), home_position.x() + 0.02, 1e-12);
}

// The file's wall 1 cm ahead of home along x, and a box a command sets.
class WorkspaceAndWall : public Workspace {
 protected:
  WorkspaceAndWall()
      : Workspace("frozen_state_timeout_s: 0\nwalls:\n  - {point: [" + aheadOfHome(0.01) +
                  ", 0, 0], normal: [1, 0, 0]}\n") {}

  static std::string aheadOfHome(double dx) {
    CartesianWrapper probe(fr3Config(kCartesianImpedancePlugin, "frozen_state_timeout_s: 0\n"));
    probe.activate(restingAt(probe.controller(), fr3Home()));
    return std::to_string(probe.measuredPose().tcp_position.x() + dx);
  }
};

TEST_F(WorkspaceAndWall, BothApply) {
  // The box reaches 2 cm ahead along x, the wall 1 cm; the box is 3 cm wide along y.
  ASSERT_TRUE(wrapper
                  .submit(box(home_position - Eigen::Vector3d(0.1, 0.03, 0.1),
                              home_position + Eigen::Vector3d(0.02, 0.03, 0.1)))
                  .accepted);
  CartesianCommand command = reach(0.05);
  command.position.y() += 0.05;
  ASSERT_TRUE(wrapper.submit(command).accepted);
  cycles(1);
  EXPECT_NEAR(reference().x(), std::stod(aheadOfHome(0.01)), 1e-6) << "the file's wall";
  EXPECT_NEAR(reference().y(), home_position.y() + 0.03, 1e-12) << "the box's face";
  // Zeros: the file's wall alone, the stage still on.
  ASSERT_TRUE(wrapper.submit(box(Eigen::Vector3d::Zero(), Eigen::Vector3d::Zero())).accepted);
  cycles(1);
  EXPECT_TRUE(walls().enabled());
  EXPECT_NEAR(reference().y(), home_position.y() + 0.05, 1e-12);
}

TEST_F(WorkspaceAndWall, ABoxWithNoRoomInsideTheWallsIsRefused) {
  // Everything of it lies 3 to 30 cm ahead, past the wall 1 cm ahead.
  const Verdict verdict = wrapper.submit(box(home_position + Eigen::Vector3d(0.03, -0.1, -0.1),
                                             home_position + Eigen::Vector3d(0.3, 0.1, 0.1)));
  EXPECT_EQ(verdict.reason, RejectionReason::kInvalidWorkspace);
  EXPECT_NE(verdict.message.find("no room"), std::string::npos) << verdict.message;
  EXPECT_FALSE(walls().boxCommanded());
}

TEST(WorkspaceConfig, TheInitialCommandCannotSetABox) {
  try {
    (void)fr3Config(
        kCartesianImpedancePlugin,
        "initial:\n  workspace_min: [0.1, -0.5, 0.1]\n  workspace_max: [0.8, 0.5, 0.9]\n");
    FAIL() << "read";
  } catch (const InputError& error) {
    EXPECT_NE(std::string(error.what()).find("boxes:"), std::string::npos) << error.what();
  }
}

}  // namespace
}  // namespace comply::pipeline::test
