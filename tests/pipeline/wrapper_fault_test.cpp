// FAULT handling (docs/design.md, "Safety semantics"): a law that fails on activation is refused
// before any torque is sent; a law that fails in the cycle, or an unusable joint state, switches to
// the controlled stop (gravity and braking within the effort limits, then a hold where the arm came
// to rest) until an explicit reset, and only a reset leaves it: with the measured pose held.

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>
#include <utility>

#include "comply/pipeline/wrapper.hpp"
#include "comply/plugin/abi.h"
#include "wrapper_support.hpp"

namespace comply::pipeline::test {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
constexpr double kTolerance = 1e-9;

/// Per-joint fault damping, all different so a mix-up of joints shows.
const JointVector kFaultDamping = (JointVector(kFr3Dof) << 1, 2, 3, 4, 5, 6, 7).finished();

/// The Cartesian law refuses damping ratios when told not to compute the mass matrix: a law that
/// is fine on activation (absolute damping) and fails in the cycle once a sender streams ratios.
std::string ratioRefusingCartesian(double rate_limit) {
  return "plugin_parameters:\n"
         "  inertia_aware_damping: 0\n"
         "initial:\n"
         "  damping_mode: absolute\n"
         "fault_damping: [1, 2, 3, 4, 5, 6, 7]\n"
         // A rate limit far below what the gains need is the point: the gain bound's torque-rate
         // part would refuse them.
         "validation: {rate_limit_swing_nm: 0}\n"
         "torque_rate_limit_nm_per_s: " +
         std::to_string(rate_limit) + "\n";
}

CartesianCommand damping(double stamp_s, DampingMode mode) {
  CartesianCommand command = CartesianCommand::zero(kFr3Dof);
  command.stamp_s = stamp_s;
  command.fields = CommandField::kDamping;
  command.damping_mode = mode;
  command.damping_translational = 45.0 * Eigen::Matrix3d::Identity();
  command.damping_rotational = 3.0 * Eigen::Matrix3d::Identity();
  command.damping_ratio.setOnes();
  return command;
}

JointState moving(JointState state, double speed) {
  state.velocity.setConstant(speed);
  return state;
}

/// The controlled stop's torque at `state`, a moving one (safe_hold.hpp): gravity and, per joint,
/// damping max(fault_damping, m / 2T) within what the effort limit leaves beside gravity.
JointVector holdingTorque(const Controller& core, const JointState& state) {
  const CycleParameters& parameters = core.resolved().parameters;
  const JointVector gravity = gravityAt(core, state.position);
  JointVector torque = gravity;
  for (int i = 0; i < kFr3Dof; ++i) {
    const double gain = std::max(kFaultDamping[i], parameters.joint_inertia[i] / (2.0 * kPeriod));
    const double brake = gain * state.velocity[i];
    const double available = parameters.effort_limit[i] - std::abs(gravity[i]);
    torque[i] -= std::isfinite(brake) ? std::clamp(brake, -available, available) : 0.0;
  }
  return torque;
}

// ---- activation -------------------------------------------------------------------------------

void expectActivationRefused(const std::string& fixture, plugin::PluginErrc code,
                             const std::string& reason) {
  SCOPED_TRACE(fixture);
  JointWrapper wrapper(fr3Config(fixture));
  const JointState state = restingAt(wrapper.controller(), fr3Home());
  try {
    wrapper.activate(state);
    ADD_FAILURE() << "activation accepted a failing law";
  } catch (const plugin::PluginError& error) {
    EXPECT_EQ(error.code(), code) << error.what();
    EXPECT_NE(std::string(error.what()).find(reason), std::string::npos) << error.what();
  }
  EXPECT_EQ(wrapper.diagnostics().state, WrapperState::kInactive);
  TorqueBuffer torque;
  EXPECT_EQ(wrapper.update(state, kPeriod, torque.span()), CycleStatus::kInactive);
  EXPECT_EQ(torque.values, TorqueBuffer{}.values) << "a refused law wrote torque";
}

TEST(WrapperFault, ActivationRefusesALawWhoseTrialStepFails) {
  expectActivationRefused(kStepErrorPlugin, plugin::PluginErrc::kTrialStepFailed,
                          "fixture step error");
  expectActivationRefused(kStepNanPlugin, plugin::PluginErrc::kNonFiniteOutput, kStepNanPlugin);
}

TEST(WrapperFault, ActivationRefusesALawWhoseActivateThrows) {
  expectActivationRefused(kThrowingActivatePlugin, plugin::PluginErrc::kTrialStepFailed,
                          "activate() failed");
}

TEST(WrapperFault, ExceptionFromAPluginStepIsAFaultNotACrash) {
  JointWrapper wrapper(fr3Config(kThrowingPlugin));
  const JointState rest = restingAt(wrapper.controller(), fr3Home());
  wrapper.activate(rest);  // the trial step returns; every later step throws
  TorqueBuffer torque;
  EXPECT_EQ(wrapper.update(rest, kPeriod, torque.span()), CycleStatus::kFault);
  COMPLY_EXPECT_JOINTS_NEAR(torque.values, holdingTorque(wrapper.controller(), rest), kTolerance);
  const DiagnosticsSnapshot diagnostics = wrapper.diagnostics();
  EXPECT_EQ(diagnostics.faults, 1U);
  EXPECT_NE(diagnostics.last_fault.find("plugin: step threw an exception"), std::string::npos)
      << diagnostics.last_fault;
}

// What the host reads of a message with no NUL: the buffer's 127 characters, never past it.
const std::string kUnterminatedReason(COMPLY_MESSAGE_CAPACITY - 1, 'x');

TEST(WrapperFault, AnUnterminatedMessageIsReadOnlyToTheEndOfItsBuffer) {
  JointWrapper wrapper(fr3Config(kUnterminatedErrorPlugin));
  const JointState rest = restingAt(wrapper.controller(), fr3Home());
  wrapper.activate(rest);  // at rest the fixture's step succeeds
  TorqueBuffer torque;
  EXPECT_EQ(wrapper.update(moving(rest, 0.1), kPeriod, torque.span()), CycleStatus::kFault);
  EXPECT_EQ(wrapper.diagnostics().last_fault, "plugin: " + kUnterminatedReason);
}

TEST(WrapperFault, AnUnterminatedMessageFromTheTrialStepIsReadOnlyToTheEndOfItsBuffer) {
  JointWrapper wrapper(fr3Config(kUnterminatedErrorPlugin));
  try {
    wrapper.activate(moving(restingAt(wrapper.controller(), fr3Home()), 0.1));
    ADD_FAILURE() << "activation accepted a failing law";
  } catch (const plugin::PluginError& error) {
    const std::string message = error.what();
    EXPECT_EQ(error.code(), plugin::PluginErrc::kTrialStepFailed) << message;
    const std::string suffix = ": " + kUnterminatedReason;
    ASSERT_GE(message.size(), suffix.size()) << message;
    EXPECT_EQ(message.substr(message.size() - suffix.size()), suffix) << message;
  }
}

TEST(WrapperFault, HoldingTorqueStaysFiniteWhenTheDampingOverflows) {
  // A finite but absurd velocity passes the state check; the law's torque overflows (FAULT) and
  // so does the holding damping: the hold is then gravity alone, never the last (law's) output.
  JointWrapper wrapper(fr3Config(kJointImpedancePlugin, "torque_rate_limit_nm_per_s: 1.0e9"));
  const JointState rest = restingAt(wrapper.controller(), fr3Home());
  wrapper.activate(rest);
  TorqueBuffer torque;
  ASSERT_EQ(wrapper.update(moving(rest, 0.5), kPeriod, torque.span()), CycleStatus::kOk);
  JointState broken = rest;
  broken.velocity[0] = 1e308;
  EXPECT_EQ(wrapper.update(broken, kPeriod, torque.span()), CycleStatus::kFault);
  ASSERT_TRUE(torque.values.allFinite()) << torque.values.transpose();
  JointState without_joint_0 = broken;
  without_joint_0.velocity[0] = 0.0;
  COMPLY_EXPECT_JOINTS_NEAR(torque.values, holdingTorque(wrapper.controller(), without_joint_0),
                            kTolerance);
}

// ---- a law failing in the cycle ---------------------------------------------------------------

/// A wrapper on the FR3 and the torque of its cycles.
template <typename WrapperType>
class WrapperFixture : public ::testing::Test {
 protected:
  explicit WrapperFixture(WrapperConfig config) : wrapper(std::move(config)) {}

  CycleStatus cycle(const JointState& state) {
    return wrapper.update(state, kPeriod, torque.span());
  }

  WrapperType wrapper;
  TorqueBuffer torque;
};

class CartesianLawFault : public WrapperFixture<CartesianWrapper> {
 protected:
  explicit CartesianLawFault(double rate_limit = kNoRateLimit)
      : WrapperFixture(fr3Config(kCartesianImpedancePlugin, ratioRefusingCartesian(rate_limit))) {}

  void SetUp() override {
    ASSERT_EQ(wrapper.controller().effortLimit().size(), kFr3Dof);
    rest = restingAt(wrapper.controller(), fr3Home());
    wrapper.activate(rest);
    ASSERT_EQ(cycle(rest), CycleStatus::kOk);
  }

  JointState rest;
};

TEST_F(CartesianLawFault, FailingStepHoldsTheArmUntilReset) {
  const JointState state = moving(rest, 0.1);
  ASSERT_EQ(cycle(state), CycleStatus::kOk);
  ASSERT_TRUE(wrapper.submit(damping(1.0, DampingMode::kRatio)).accepted);

  EXPECT_EQ(cycle(state), CycleStatus::kFault);
  COMPLY_EXPECT_JOINTS_NEAR(torque.values, holdingTorque(wrapper.controller(), state), kTolerance);
  DiagnosticsSnapshot diagnostics = wrapper.diagnostics();
  EXPECT_EQ(diagnostics.state, WrapperState::kFault);
  EXPECT_EQ(diagnostics.faults, 1U);
  EXPECT_NE(diagnostics.last_error.find("plugin: damping ratios need inertia_aware_damping: 1"),
            std::string::npos)
      << diagnostics.last_error;

  // A valid command is accepted but does not leave FAULT by itself.
  ASSERT_TRUE(wrapper.submit(damping(2.0, DampingMode::kAbsolute)).accepted);
  for (int i = 0; i < 50; ++i) {
    ASSERT_EQ(cycle(state), CycleStatus::kFault) << "cycle " << i;
  }
  COMPLY_EXPECT_JOINTS_NEAR(torque.values, holdingTorque(wrapper.controller(), state), kTolerance);
  EXPECT_EQ(wrapper.diagnostics().faults, 1U) << "one fault, counted once";

  wrapper.reset();
  EXPECT_EQ(cycle(rest), CycleStatus::kOk);
  // Back on the law, whose reference is still the seeded pose: at rest it adds nothing.
  COMPLY_EXPECT_JOINTS_NEAR(torque.values, rest.effort, kTolerance);
  diagnostics = wrapper.diagnostics();
  EXPECT_EQ(diagnostics.state, WrapperState::kActive);
  EXPECT_EQ(diagnostics.faults, 1U);
}

TEST_F(CartesianLawFault, ResetWithTheFailingCommandStillInForceFaultsAgain) {
  ASSERT_TRUE(wrapper.submit(damping(1.0, DampingMode::kRatio)).accepted);
  EXPECT_EQ(cycle(rest), CycleStatus::kFault);
  wrapper.reset();
  EXPECT_EQ(cycle(rest), CycleStatus::kFault);
  EXPECT_EQ(wrapper.diagnostics().faults, 2U);
}

TEST_F(CartesianLawFault, AResetHoldsTheMeasuredPoseNotTheTargetInForceAtTheFault) {
  // A target 5 cm off and a feedforward push in force when the law fails: the reset must not put
  // them back (the arm stopped elsewhere; they may be what caused the fault).
  CartesianCommand target = CartesianCommand::zero(kFr3Dof);
  target.stamp_s = 0.5;
  target.fields = CommandField::kPosition | CommandField::kWrenchFeedforward;
  target.position = wrapper.measuredPose().tcp_position + Eigen::Vector3d(0.05, 0.0, 0.0);
  target.orientation = wrapper.measuredPose().tcp_orientation;
  target.wrench_feedforward << 10.0, 0.0, 0.0, 0.0, 0.0, 1.0;
  ASSERT_TRUE(wrapper.submit(target).accepted);
  ASSERT_EQ(cycle(rest), CycleStatus::kOk);
  ASSERT_TRUE(wrapper.submit(damping(1.0, DampingMode::kRatio)).accepted);
  ASSERT_EQ(cycle(rest), CycleStatus::kFault);
  ASSERT_TRUE(wrapper.submit(damping(2.0, DampingMode::kAbsolute)).accepted);
  JointState stopped = rest;
  stopped.position[0] += 0.02;  // where the stop left the arm
  ASSERT_EQ(cycle(stopped), CycleStatus::kFault);
  wrapper.reset();
  ASSERT_EQ(cycle(stopped), CycleStatus::kOk);
  const auto& in_force = std::get<comply_cartesian_command>(wrapper.controller().activeCommand());
  const MeasuredPose measured = wrapper.measuredPose();
  for (int axis = 0; axis < 3; ++axis) {
    EXPECT_DOUBLE_EQ(in_force.position[axis], measured.tcp_position[axis]) << axis;
  }
  for (const double value : in_force.wrench_feedforward) {
    EXPECT_EQ(value, 0.0) << "the feedforward in force at the fault was re-armed";
  }
  EXPECT_EQ(in_force.damping_mode, COMPLY_DAMPING_ABSOLUTE) << "the gains sent since stay";
}

TEST_F(CartesianLawFault, ResetBeforeAFaultDoesNotClearIt) {
  // A reset while nothing is wrong must not stay armed and silently undo a later fault.
  wrapper.reset();
  ASSERT_EQ(cycle(rest), CycleStatus::kOk);
  ASSERT_TRUE(wrapper.submit(damping(1.0, DampingMode::kRatio)).accepted);
  EXPECT_EQ(cycle(rest), CycleStatus::kFault);
  ASSERT_TRUE(wrapper.submit(damping(2.0, DampingMode::kAbsolute)).accepted);
  EXPECT_EQ(cycle(rest), CycleStatus::kFault);
}

class RateLimitedCartesianLawFault : public CartesianLawFault {
 protected:
  static constexpr double kRateLimit = 100.0;  // N m/s: 0.1 N m per 1 ms cycle
  RateLimitedCartesianLawFault() : CartesianLawFault(kRateLimit) {}
};

TEST_F(RateLimitedCartesianLawFault, HoldingTorqueIsRateLimited) {
  ASSERT_TRUE(wrapper.submit(damping(1.0, DampingMode::kRatio)).accepted);
  // Every joint brakes at 0.02 rad/s, m / 2T of it (up to 7.2 N m on joint 2): a step the rate
  // limit spreads over up to 72 cycles, inside the frozen-state timeout (0.1 s) this repeated
  // state would otherwise reach.
  const JointState state = moving(rest, 0.02);
  const JointVector target = holdingTorque(wrapper.controller(), state);
  JointVector previous = torque.values;
  const std::uint64_t hits_before = wrapper.diagnostics().rate_limit_hits;
  for (int i = 0; i < 95; ++i) {
    ASSERT_EQ(cycle(state), CycleStatus::kFault);
    EXPECT_LE(maxDifference(torque.values, previous), kRateLimit * kPeriod * (1.0 + 1e-9))
        << "cycle " << i;
    previous = torque.values;
  }
  EXPECT_GT(wrapper.diagnostics().rate_limit_hits, hits_before);
  COMPLY_EXPECT_JOINTS_NEAR(torque.values, target, kTolerance);
}

// ---- an unusable joint state ------------------------------------------------------------------

class JointStateFault : public WrapperFixture<JointWrapper> {
 protected:
  JointStateFault()
      : WrapperFixture(fr3Config(kJointImpedancePlugin,
                                 "fault_damping: [1, 2, 3, 4, 5, 6, 7]\n"
                                 "torque_rate_limit_nm_per_s: " +
                                     std::to_string(kNoRateLimit))) {}

  void SetUp() override {
    good = moving(restingAt(wrapper.controller(), fr3Home()), 0.1);
    broken = good;
    broken.position[3] = kNaN;
    wrapper.activate(good);
    ASSERT_EQ(cycle(good), CycleStatus::kOk);
  }

  JointState good;
  JointState broken;
};

TEST_F(JointStateFault, NanStateHoldsTheArmAtTheLastGoodStateUntilReset) {
  EXPECT_EQ(cycle(broken), CycleStatus::kFault);
  // The last good state's velocity is stale: braking against it would push the arm one way for
  // as long as the stream stays broken. Gravity alone, and the hardware's hold asked for.
  COMPLY_EXPECT_JOINTS_NEAR(torque.values, gravityAt(wrapper.controller(), good.position),
                            kTolerance);
  EXPECT_TRUE(wrapper.wantsHold());
  EXPECT_EQ(cycle(broken), CycleStatus::kFault);
  COMPLY_EXPECT_JOINTS_NEAR(torque.values, gravityAt(wrapper.controller(), good.position),
                            kTolerance);
  const DiagnosticsSnapshot diagnostics = wrapper.diagnostics();
  EXPECT_EQ(diagnostics.faults, 1U);
  EXPECT_NE(diagnostics.last_error.find("state: "), std::string::npos) << diagnostics.last_error;

  EXPECT_EQ(cycle(broken), CycleStatus::kFault);
  EXPECT_EQ(cycle(good), CycleStatus::kFault) << "a good state alone does not leave FAULT";
  EXPECT_EQ(wrapper.diagnostics().faults, 1U);

  wrapper.reset();
  EXPECT_EQ(cycle(good), CycleStatus::kOk);
  EXPECT_EQ(wrapper.diagnostics().state, WrapperState::kActive);
}

TEST(WrapperFault, NanStateInTheFirstCycleHoldsAtTheActivationState) {
  // The activation state is the last usable one until a cycle measures another: the hold must be
  // built from it, not from no state (zero gravity, the arm drops) or an earlier activation's.
  JointWrapper wrapper(fr3Config(kJointImpedancePlugin,
                                 "fault_damping: [1, 2, 3, 4, 5, 6, 7]\n"
                                 "torque_rate_limit_nm_per_s: " +
                                     std::to_string(kNoRateLimit)));
  TorqueBuffer torque;
  const JointState earlier = restingAt(wrapper.controller(), offset(fr3Home(), 1, 0.4));
  wrapper.activate(earlier);
  ASSERT_EQ(wrapper.update(earlier, kPeriod, torque.span()), CycleStatus::kOk);
  wrapper.deactivate();

  const JointState good = moving(restingAt(wrapper.controller(), fr3Home()), 0.1);
  JointState broken = good;
  broken.position[3] = kNaN;
  wrapper.activate(good);
  EXPECT_EQ(wrapper.update(broken, kPeriod, torque.span()), CycleStatus::kFault);
  COMPLY_EXPECT_JOINTS_NEAR(torque.values, gravityAt(wrapper.controller(), good.position),
                            kTolerance);
}

TEST_F(JointStateFault, ResetIsRefusedWhileTheStateIsStillUnusable) {
  ASSERT_EQ(cycle(broken), CycleStatus::kFault);
  wrapper.reset();
  // The law must not run on the last good state as if it were current.
  EXPECT_EQ(cycle(broken), CycleStatus::kFault);
  COMPLY_EXPECT_JOINTS_NEAR(torque.values, gravityAt(wrapper.controller(), good.position),
                            kTolerance);
  // Refused, not postponed: recovering later needs a reset once the state is good again.
  EXPECT_EQ(cycle(good), CycleStatus::kFault);
  wrapper.reset();
  EXPECT_EQ(cycle(good), CycleStatus::kOk);
}

}  // namespace
}  // namespace comply::pipeline::test
