// Command watchdog (docs/design.md, "Safety semantics"): when senders go quiet for
// command_timeout_s, "hold" keeps the last pose reference but drops any motion (velocity, twist)
// reference, and "reanchor" moves the reference to the measured pose. Either way, a later partial
// command builds on what the cycle holds, not on what the sender last sent.

#include <gtest/gtest.h>

#include <string>

#include "comply/pipeline/wrapper.hpp"
#include "wrapper_support.hpp"

namespace comply::pipeline::test {
namespace {

constexpr double kTolerance = 1e-9;
constexpr double kTimeout = 0.02;  // s: 20 cycles at 1 kHz
constexpr int kTimeoutCycles = 20;

std::string watchdogLines(const std::string& behavior, const std::string& more = {}) {
  return "command_timeout_s: " + std::to_string(kTimeout) + "\n" + "timeout_behavior: " + behavior +
         "\n" + "torque_rate_limit_nm_per_s: " + std::to_string(kNoRateLimit) + "\n" + more;
}

/// Runs `law` (one cycle, the law's torque) past the timeout: one timeout, and the reference
/// re-anchored at the arm, so the law pulls nowhere.
template <typename WrapperType, typename Law>
void expectReanchoredAfterTimeout(const WrapperType& wrapper, const Law& law) {
  for (int i = 0; i < 2 * kTimeoutCycles; ++i) {
    law();
  }
  EXPECT_EQ(wrapper.diagnostics().watchdog_timeouts, 1U);
  COMPLY_EXPECT_JOINTS_NEAR(law(), JointVector::Zero(kFr3Dof), kTolerance);
}

template <typename WrapperType>
class Watchdog : public ::testing::Test {
 protected:
  Watchdog(const std::string& plugin, const std::string& lines)
      : wrapper(fr3Config(plugin, lines)) {}

  void SetUp() override {
    state = restingAt(wrapper.controller(), fr3Home());
    wrapper.activate(state);
  }

  JointVector lawTorque() {
    EXPECT_EQ(wrapper.update(state, kPeriod, torque.span()), CycleStatus::kOk);
    return torque.values - state.effort;
  }

  /// Runs cycles until the law's torque falls below `tolerance` (at most `limit` cycles);
  /// returns how many cycles that took, counting the first one without torque.
  int cyclesUntilTorqueVanishes(double tolerance, int limit = 10 * kTimeoutCycles) {
    for (int cycle = 1; cycle <= limit; ++cycle) {
      if (lawTorque().cwiseAbs().maxCoeff() < tolerance) {
        return cycle;
      }
    }
    return -1;
  }

  WrapperType wrapper;
  JointState state;
  TorqueBuffer torque;
};

/// A joint command that sets the stiffness alone, every joint `stiffness` [N m/rad].
JointCommand jointStiffnessOnly(double stamp_s, double stiffness) {
  JointCommand gains = JointCommand::zero(kFr3Dof);
  gains.stamp_s = stamp_s;
  gains.fields = CommandField::kStiffness;
  gains.stiffness.setConstant(stiffness);
  return gains;
}

/// A Cartesian command that sets the stiffness alone, stamped `stamp_s`.
CartesianCommand stiffnessOnly(double stamp_s) {
  CartesianCommand gains = CartesianCommand::zero(kFr3Dof);
  gains.stamp_s = stamp_s;
  gains.fields = CommandField::kStiffness;
  gains.stiffness_translational = 800.0 * Eigen::Matrix3d::Identity();
  gains.stiffness_rotational = 40.0 * Eigen::Matrix3d::Identity();
  return gains;
}

// ---- hold -------------------------------------------------------------------------------------

class JointHold : public Watchdog<JointWrapper> {
 protected:
  JointHold() : Watchdog(kJointImpedancePlugin, watchdogLines("hold")) {}

  void submitVelocity(double stamp_s, double velocity) {
    JointCommand command = JointCommand::zero(kFr3Dof);
    command.stamp_s = stamp_s;
    command.fields = CommandField::kVelocity;
    command.velocity[0] = velocity;
    ASSERT_TRUE(wrapper.submit(command).accepted);
  }
};

TEST_F(JointHold, TimeoutDropsTheVelocityReference) {
  submitVelocity(1.0, 0.1);
  // Default damping 10 N m s/rad pulls joint 1 towards 0.1 rad/s: 1 N m while commands are fresh.
  const JointVector pulling = lawTorque();
  EXPECT_NEAR(pulling[0], 1.0, kTolerance);

  // The first cycle took the command; the timeout falls 20 cycles later.
  const int cycles = 1 + cyclesUntilTorqueVanishes(kTolerance);
  EXPECT_GE(cycles, kTimeoutCycles) << "the watchdog fired early";
  EXPECT_LE(cycles, kTimeoutCycles + 2) << "the watchdog fired late";
  EXPECT_EQ(wrapper.diagnostics().watchdog_timeouts, 1U);

  for (int i = 0; i < 5 * kTimeoutCycles; ++i) {
    lawTorque();
  }
  EXPECT_EQ(wrapper.diagnostics().watchdog_timeouts, 1U) << "one silence, one timeout";
}

TEST_F(JointHold, PartialCommandAfterTheTimeoutDoesNotReviveTheVelocity) {
  submitVelocity(1.0, 0.1);
  ASSERT_GT(cyclesUntilTorqueVanishes(kTolerance), 0);

  ASSERT_TRUE(wrapper.submit(jointStiffnessOnly(2.0, 150.0)).accepted);
  COMPLY_EXPECT_JOINTS_NEAR(lawTorque(), JointVector::Zero(kFr3Dof), kTolerance);
  EXPECT_EQ(wrapper.lastAccepted().velocity, JointVector(JointVector::Zero(kFr3Dof)));

  // A fresh velocity reference works again, and the new timeout is counted again.
  submitVelocity(3.0, -0.2);
  EXPECT_NEAR(lawTorque()[0], -2.0, kTolerance);
  ASSERT_GT(cyclesUntilTorqueVanishes(kTolerance), 0);
  EXPECT_EQ(wrapper.diagnostics().watchdog_timeouts, 2U);
}

class CartesianHold : public Watchdog<CartesianWrapper> {
 protected:
  CartesianHold()
      : Watchdog(kCartesianImpedancePlugin,
                 watchdogLines("hold", "initial:\n  damping_mode: absolute\n")) {}
};

TEST_F(CartesianHold, TimeoutDropsTheTwistReference) {
  CartesianCommand command = CartesianCommand::zero(kFr3Dof);
  command.stamp_s = 1.0;
  command.fields = CommandField::kVelocity;
  command.twist[0] = 0.05;  // m/s along x; 45 N s/m of damping pull 2.25 N along it
  ASSERT_TRUE(wrapper.submit(command).accepted);
  EXPECT_GT(lawTorque().cwiseAbs().maxCoeff(), 0.1);

  const int cycles = 1 + cyclesUntilTorqueVanishes(kTolerance);
  EXPECT_GE(cycles, kTimeoutCycles);
  EXPECT_LE(cycles, kTimeoutCycles + 2);
  EXPECT_EQ(wrapper.diagnostics().watchdog_timeouts, 1U);

  // A later stiffness-only command keeps the pose reference and does not revive the twist.
  ASSERT_TRUE(wrapper.submit(stiffnessOnly(2.0)).accepted);
  COMPLY_EXPECT_JOINTS_NEAR(lawTorque(), JointVector::Zero(kFr3Dof), kTolerance);
  EXPECT_TRUE(wrapper.lastAccepted().twist.isZero());
}

// ---- reanchor ---------------------------------------------------------------------------------

class JointReanchor : public Watchdog<JointWrapper> {
 protected:
  JointReanchor() : Watchdog(kJointImpedancePlugin, watchdogLines("reanchor")) {}
};

TEST_F(JointReanchor, JointReferenceMovesToTheMeasuredPosition) {
  const JointVector home = fr3Home();
  const auto law = [this] { return lawTorque(); };

  JointCommand target = JointCommand::zero(kFr3Dof);
  target.stamp_s = 1.0;
  target.fields = CommandField::kPosition;
  target.position = offset(home, 0, 0.05);
  ASSERT_TRUE(wrapper.submit(target).accepted);
  EXPECT_NEAR(law()[0], 100.0 * 0.05, kTolerance);

  // The arm gets part of the way (an obstacle) and the sender goes quiet.
  const JointVector stuck = offset(home, 0, 0.03);
  state = restingAt(wrapper.controller(), stuck);
  EXPECT_NEAR(law()[0], 100.0 * 0.02, kTolerance);
  expectReanchoredAfterTimeout(wrapper, law);

  // Gains only: the re-anchored reference stays, so nothing pulls back to the old target.
  ASSERT_TRUE(wrapper.submit(jointStiffnessOnly(2.0, 200.0)).accepted);
  COMPLY_EXPECT_JOINTS_NEAR(law(), JointVector::Zero(kFr3Dof), kTolerance);
  COMPLY_EXPECT_JOINTS_NEAR(wrapper.lastAccepted().position, stuck, 0.0);
}

class CartesianReanchor : public Watchdog<CartesianWrapper> {
 protected:
  // A stiff nullspace so that a nullspace target left behind would show in the torque.
  CartesianReanchor()
      : Watchdog(kCartesianImpedancePlugin,
                 watchdogLines("reanchor",
                               "initial:\n  damping_mode: absolute\n  nullspace_stiffness: 20\n")) {
  }
};

TEST_F(CartesianReanchor, CartesianReferenceAndNullspaceTargetMoveToTheMeasuredPose) {
  const JointVector home = fr3Home();
  const CartesianCommand seeded = wrapper.lastAccepted();
  const auto law = [this] { return lawTorque(); };

  CartesianCommand target = CartesianCommand::zero(kFr3Dof);
  target.stamp_s = 1.0;
  target.fields = CommandField::kPosition;
  target.position = seeded.position + Eigen::Vector3d(0.03, 0.0, 0.0);
  target.orientation = seeded.orientation;
  ASSERT_TRUE(wrapper.submit(target).accepted);
  EXPECT_GT(law().cwiseAbs().maxCoeff(), 1.0);

  // Pushed aside, elbow included: both the TCP pose and the joint configuration changed.
  const JointVector pushed = offset(offset(home, 0, 0.04), 2, 0.1);
  state = restingAt(wrapper.controller(), pushed);
  expectReanchoredAfterTimeout(wrapper, law);

  ASSERT_TRUE(wrapper.submit(stiffnessOnly(2.0)).accepted);
  COMPLY_EXPECT_JOINTS_NEAR(law(), JointVector::Zero(kFr3Dof), kTolerance);

  const CartesianCommand in_force = wrapper.lastAccepted();
  EXPECT_TRUE(in_force.position.isApprox(wrapper.controller().modelData().tip_position, 1e-15));
  COMPLY_EXPECT_JOINTS_NEAR(in_force.nullspace_position, pushed, 0.0);
}

}  // namespace
}  // namespace comply::pipeline::test
