// Walls through the wrapper on the FR3 (virtual_walls.hpp): a chunk's reference is kept inside
// them as a command's is; a FAULT's hold shows no barrier force; a barrier damper that would ring
// on the TCP's lightest apparent mass (under any Cartesian law: a command may set a box), and
// walls under a joint law, are refused when the controller is resolved.

#include <gtest/gtest.h>

#include <algorithm>
#include <limits>
#include <string>

#include "comply/core/input_error.hpp"
#include "comply/pipeline/resolved_controller.hpp"
#include "comply/pipeline/wrapper.hpp"
#include "wrapper_support.hpp"

namespace comply::pipeline::test {
namespace {

const comply_cartesian_command& lawCommand(const CartesianWrapper& wrapper) {
  return std::get<comply_cartesian_command>(wrapper.controller().lawBus());
}

/// Where a wall 2 cm ahead of the FR3's home TCP along base x is (found on a probe wrapper), as
/// the controller file writes it.
std::string wallAheadOfHome() {
  CartesianWrapper probe(fr3Config(kCartesianImpedancePlugin, "frozen_state_timeout_s: 0.0\n"));
  JointState state = restingAt(probe.controller(), fr3Home());
  probe.activate(state);
  return std::to_string(probe.measuredPose().tcp_position.x() + 0.02);
}

class WrapperWalls : public ::testing::Test {
 protected:
  void SetUp() override {
    wrapper_ = std::make_unique<CartesianWrapper>(
        fr3Config(kCartesianImpedancePlugin, "frozen_state_timeout_s: 0.0\nwalls:\n  - {point: [" +
                                                 wall_x_text_ + ", 0, 0], normal: [1, 0, 0]}\n"));
    state_ = restingAt(wrapper_->controller(), fr3Home());
    wrapper_->activate(state_);
    home_ = wrapper_->measuredPose().tcp_position;
  }
  CycleStatus cycle() { return wrapper_->update(state_, kPeriod, torque_.span()); }

  const std::string wall_x_text_ = wallAheadOfHome();
  const double wall_x_ = std::stod(wall_x_text_);
  std::unique_ptr<CartesianWrapper> wrapper_;
  JointState state_;
  TorqueBuffer torque_;
  Eigen::Vector3d home_;
};

TEST_F(WrapperWalls, AChunkThroughAWallIsKeptOnItsSide) {
  // Six waypoints 1 cm apart along +x, 50 ms apart: the last 4 cm past where the wall is.
  CartesianChunk chunk;
  chunk.stamp_s = 1.0;
  chunk.fields = CommandField::kPosition;
  for (int k = 1; k <= 6; ++k) {
    ChunkWaypoint<CartesianCommand> waypoint{0.05 * k, CartesianCommand::zero(kFr3Dof)};
    waypoint.command.position = home_ + Eigen::Vector3d(0.01 * k, 0.0, 0.0);
    waypoint.command.orientation = wrapper_->measuredPose().tcp_orientation;
    chunk.waypoints.push_back(waypoint);
  }
  ASSERT_TRUE(wrapper_->submitChunk(chunk, 0.0).accepted);
  const double wall_x = wall_x_;
  double furthest_played = -std::numeric_limits<double>::infinity();
  double furthest_law = -std::numeric_limits<double>::infinity();
  for (int i = 0; i < 400; ++i) {
    ASSERT_EQ(cycle(), CycleStatus::kOk) << i;
    const auto& played = std::get<comply_cartesian_command>(wrapper_->controller().activeCommand());
    furthest_played = std::max(furthest_played, played.position[0]);
    furthest_law = std::max(furthest_law, lawCommand(*wrapper_).position[0]);
    // On the wall the reference's motion out through it is gone too.
    if (lawCommand(*wrapper_).position[0] >= wall_x - 1e-12) {
      EXPECT_LE(lawCommand(*wrapper_).twist[0], 0.0) << i;
    }
  }
  EXPECT_GT(furthest_played, wall_x + 0.03) << "the chunk did not play past the wall";
  EXPECT_LE(furthest_law, wall_x + 1e-12);
  EXPECT_GT(furthest_law, wall_x - 1e-6) << "the law's reference never reached the wall";
  EXPECT_GT(wrapper_->diagnostics().wall_reference_hits, 0U);
}

TEST_F(WrapperWalls, AFaultsHoldShowsNoBarrierForce) {
  // The TCP 2 cm from the wall moving at it: the barrier brakes.
  state_.velocity.setZero();
  const Eigen::Matrix<double, 6, Eigen::Dynamic> jacobian =
      wrapper_->controller().modelData().jacobian.leftCols(kFr3Dof);
  state_.velocity.head(kFr3Dof) =
      jacobian.completeOrthogonalDecomposition().solve(Vector6d(0.3, 0, 0, 0, 0, 0));
  ASSERT_EQ(cycle(), CycleStatus::kOk);
  ASSERT_LT(wrapper_->controller().walls().force().x(), -1.0);
  const double distance = wrapper_->controller().walls().distance();
  EXPECT_NEAR(distance, 0.02, 1e-3);
  // A state that is not finite: FAULT, the hold, the last usable pose's distance, no force.
  JointState broken = state_;
  broken.position[3] = std::numeric_limits<double>::quiet_NaN();
  ASSERT_EQ(wrapper_->update(broken, kPeriod, torque_.span()), CycleStatus::kFault);
  EXPECT_TRUE(wrapper_->controller().walls().force().isZero(0.0));
  EXPECT_NEAR(wrapper_->controller().walls().distance(), distance, 1e-3);
}

TEST(WrapperWallsConfig, ADamperThatWouldRingIsRefused) {
  try {
    (void)resolveController(fr3Config(
        kCartesianImpedancePlugin,
        "walls:\n  - {point: [0.8, 0, 0], normal: [1, 0, 0]}\nwall:\n  damping_n_s_per_m: 9000\n"));
    FAIL() << "resolved";
  } catch (const InputError& error) {
    const std::string message = error.what();
    EXPECT_NE(message.find("wall.damping_n_s_per_m"), std::string::npos) << message;
    EXPECT_NE(message.find("half of deadbeat"), std::string::npos) << message;
  }
  // Without walls in the file too: a command may set a box at run time.
  EXPECT_THROW((void)resolveController(
                   fr3Config(kCartesianImpedancePlugin, "wall:\n  damping_n_s_per_m: 9000\n")),
               InputError);
  // A joint law has no TCP reference to keep anywhere: never used, accepted.
  EXPECT_NO_THROW((void)resolveController(
      fr3Config(kJointImpedancePlugin, "wall:\n  damping_n_s_per_m: 9000\n")));
}

TEST(WrapperWallsConfig, WallsUnderAJointLawAreRefused) {
  try {
    (void)resolveController(
        fr3Config(kJointImpedancePlugin, "walls:\n  - {point: [0.8, 0, 0], normal: [1, 0, 0]}\n"));
    FAIL() << "resolved";
  } catch (const InputError& error) {
    EXPECT_NE(std::string(error.what()).find("need a Cartesian law"), std::string::npos)
        << error.what();
  }
}

}  // namespace
}  // namespace comply::pipeline::test
