// The gain stage on the FR3: a step in a command becomes the configured ramp (and the torque-rate
// limit, which would otherwise catch the step, never has to); with nothing to hold back the law
// reads the command bit for bit; off, the law reads the command in force itself.

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <random>
#include <string>

#include "comply/pipeline/wrapper.hpp"
#include "pose_step.hpp"
#include "wrapper_support.hpp"

namespace comply::pipeline::test {
namespace {

constexpr double kLowStiffness = 100.0;    // N/m
constexpr double kHighStiffness = 3000.0;  // N/m
constexpr double kRampRate = 10000.0;      // N/m per s: gain_ramps.translational_stiffness_per_s

const comply_cartesian_command& lawCommand(const CartesianWrapper& wrapper) {
  return std::get<comply_cartesian_command>(wrapper.controller().lawBus());
}

/// The FR3 held at home with its Cartesian reference 2 cm away along x and K = 100 N/m, settled.
class StiffnessStep : public ::testing::Test {
 protected:
  static std::string lines(bool ramps) {
    return std::string("gain_ramps:\n  enabled: ") + (ramps ? "true" : "false") +
           "\ninitial:\n  stiffness_translational: " + std::to_string(kLowStiffness) + "\n";
  }

  void start(CartesianWrapper& wrapper) {
    state = restingAt(wrapper.controller(), fr3Home());
    wrapper.activate(state);
    const CartesianCommand target = testing::poseStep(wrapper, Eigen::Vector3d(0.02, 0.0, 0.0));
    ASSERT_TRUE(wrapper.submit(target).accepted);
    for (int cycle = 0; cycle < 200; ++cycle) {
      cycleOnce(wrapper);
    }
  }

  void cycleOnce(CartesianWrapper& wrapper) {
    ASSERT_EQ(wrapper.update(state, kPeriod, torque.span()), CycleStatus::kOk);
    state.effort = torque.values;  // the arm carries what it was told
  }

  static CartesianCommand stiffnessCommand(double stiffness_n_per_m) {
    CartesianCommand command = CartesianCommand::zero(kFr3Dof);
    command.stamp_s = 2.0;
    command.fields = CommandField::kStiffness;
    command.stiffness_translational = stiffness_n_per_m * Eigen::Matrix3d::Identity();
    command.stiffness_rotational = 30.0 * Eigen::Matrix3d::Identity();
    return command;
  }

  JointState state;
  TorqueBuffer torque;
};

TEST_F(StiffnessStep, WithoutRampsTheTorqueRateLimitCatchesTheStep) {
  CartesianWrapper wrapper(fr3Config(kCartesianImpedancePlugin, lines(false)));
  start(wrapper);
  const std::uint64_t hits_before = wrapper.diagnostics().rate_limit_hits;
  ASSERT_TRUE(wrapper.submit(stiffnessCommand(kHighStiffness)).accepted);
  cycleOnce(wrapper);
  EXPECT_EQ(lawCommand(wrapper).stiffness_translational[0], kHighStiffness);
  for (int cycle = 0; cycle < 100; ++cycle) {
    cycleOnce(wrapper);
  }
  EXPECT_GT(wrapper.diagnostics().rate_limit_hits, hits_before + 10)
      << "58 N at the tool in one cycle: the 1000 N m/s limit must have clipped it";
}

TEST_F(StiffnessStep, WithRampsTheStepBecomesTheConfiguredRampAndTheRateLimitNeverBinds) {
  CartesianWrapper wrapper(fr3Config(kCartesianImpedancePlugin, lines(true)));
  start(wrapper);
  const std::uint64_t hits_before = wrapper.diagnostics().rate_limit_hits;
  ASSERT_TRUE(wrapper.submit(stiffnessCommand(kHighStiffness)).accepted);
  const int ramp_cycles =
      static_cast<int>(std::ceil((kHighStiffness - kLowStiffness) / (kRampRate * kPeriod)));
  for (int cycle = 1; cycle <= ramp_cycles + 10; ++cycle) {
    cycleOnce(wrapper);
    const double expected = std::min(kLowStiffness + cycle * kRampRate * kPeriod, kHighStiffness);
    ASSERT_NEAR(lawCommand(wrapper).stiffness_translational[0], expected, 1e-9)
        << "cycle " << cycle;
    ASSERT_NEAR(lawCommand(wrapper).stiffness_translational[8], expected, 1e-9);
    EXPECT_EQ(lawCommand(wrapper).stiffness_translational[1], 0.0) << "stays diagonal";
  }
  EXPECT_EQ(lawCommand(wrapper).stiffness_translational[0], kHighStiffness) << "lands exactly";
  EXPECT_EQ(wrapper.diagnostics().rate_limit_hits, hits_before);
  EXPECT_EQ(wrapper.diagnostics().passivity.gain_fraction, 1.0);
}

TEST_F(StiffnessStep, ATaskFrameStepTurnsAtTheConfiguredAngularRate) {
  CartesianWrapper wrapper(fr3Config(kCartesianImpedancePlugin, lines(true)));
  start(wrapper);
  CartesianCommand turn = CartesianCommand::zero(kFr3Dof);
  turn.stamp_s = 2.0;
  turn.fields = CommandField::kTaskFrame;
  turn.task_frame = Eigen::AngleAxisd(std::numbers::pi / 2, Eigen::Vector3d::UnitZ());
  ASSERT_TRUE(wrapper.submit(turn).accepted);
  const double rate_rad_per_s = 1.0;  // gain_ramps.task_frame_rad_per_s
  for (int cycle = 1; cycle <= 100; ++cycle) {
    cycleOnce(wrapper);
    const double* frame = lawCommand(wrapper).task_frame;
    const Eigen::Quaterniond in_force(frame[3], frame[0], frame[1], frame[2]);
    ASSERT_NEAR(in_force.angularDistance(Eigen::Quaterniond::Identity()),
                cycle * rate_rad_per_s * kPeriod, 1e-9);
    ASSERT_NEAR(in_force.angularDistance(turn.task_frame),
                std::numbers::pi / 2 - cycle * rate_rad_per_s * kPeriod, 1e-9);
  }
  EXPECT_NEAR(wrapper.diagnostics().passivity.gain_fraction, 0.1 / (std::numbers::pi / 2), 1e-6);
}

// ---- transparency -------------------------------------------------------------------------------

/// A smooth motion around home so every cycle computes new numbers.
JointState movingState(const JointVector& home, int cycle) {
  return test::movingState(home, cycle, 0.03, 0.3);
}

/// Runs `cycles` cycles of both wrappers on the same states and commands (new pose, gains,
/// task frame and nullspace every 50 cycles) and expects identical torques, bit for bit.
void expectSameTorques(CartesianWrapper& reference, CartesianWrapper& guarded, int cycles) {
  const JointVector home = fr3Home();
  reference.activate(movingState(home, 0));
  guarded.activate(movingState(home, 0));
  TorqueBuffer reference_torque;
  TorqueBuffer guarded_torque;
  int compared = 0;
  for (int cycle = 1; cycle <= cycles; ++cycle) {
    if (cycle % 50 == 0) {
      const double phase = 0.01 * cycle;
      CartesianCommand command = CartesianCommand::zero(kFr3Dof);
      command.stamp_s = cycle * kPeriod;
      command.fields = CommandField::kAll;
      command.position = reference.measuredPose().tcp_position +
                         Eigen::Vector3d(0.01 * std::sin(phase), 0.01 * std::cos(phase), 0.0);
      command.orientation = reference.measuredPose().tcp_orientation;
      command.stiffness_translational =
          Eigen::Vector3d(300.0 + 2000.0 * std::abs(std::sin(phase)), 800.0, 1500.0).asDiagonal();
      command.stiffness_rotational = (20.0 + 10.0 * std::sin(phase)) * Eigen::Matrix3d::Identity();
      command.damping_mode = cycle % 100 == 0 ? DampingMode::kRatio : DampingMode::kAbsolute;
      command.damping_translational = 40.0 * Eigen::Matrix3d::Identity();
      command.damping_rotational = 2.0 * Eigen::Matrix3d::Identity();
      command.damping_ratio.setConstant(0.8);
      command.task_frame = Eigen::AngleAxisd(phase, Eigen::Vector3d(0.0, 0.6, 0.8));
      command.nullspace_position = home;
      command.nullspace_stiffness.setConstant(5.0 + std::abs(std::sin(phase)));
      command.nullspace_damping.setConstant(0.5);
      ASSERT_TRUE(reference.submit(command).accepted) << reference.diagnostics().last_rejection;
      ASSERT_TRUE(guarded.submit(command).accepted);
    }
    const JointState state = movingState(home, cycle);
    ASSERT_EQ(reference.update(state, kPeriod, reference_torque.span()), CycleStatus::kOk);
    ASSERT_EQ(guarded.update(state, kPeriod, guarded_torque.span()), CycleStatus::kOk);
    for (int joint = 0; joint < kFr3Dof; ++joint) {
      ASSERT_EQ(guarded_torque.values[joint], reference_torque.values[joint])
          << "cycle " << cycle << ", joint " << joint;
    }
    ++compared;
  }
  EXPECT_EQ(compared, cycles);
}

TEST(GainGuard, OffTheLawReadsTheCommandInForceItself) {
  CartesianWrapper wrapper(fr3Config(kCartesianImpedancePlugin));
  EXPECT_EQ(&wrapper.controller().lawBus(), &wrapper.controller().activeCommand());
  EXPECT_FALSE(wrapper.diagnostics().passivity.enabled);
  CartesianWrapper guarded(fr3Config(
      kCartesianImpedancePlugin, "gain_ramps:\n  enabled: true\npassivity:\n  enabled: true\n"));
  EXPECT_NE(&guarded.controller().lawBus(), &guarded.controller().activeCommand());
}

TEST(GainGuard, WithNothingToHoldBackTheLawSeesTheCommandBitForBit) {
  CartesianWrapper reference(fr3Config(kCartesianImpedancePlugin));
  CartesianWrapper guarded(
      fr3Config(kCartesianImpedancePlugin,
                // Ramps so fast that every change arrives in one cycle.
                "gain_ramps:\n  enabled: true\n  translational_stiffness_per_s: 1.0e12\n"
                "  rotational_stiffness_per_s: 1.0e12\n  joint_stiffness_per_s: 1.0e12\n"
                "  translational_damping_per_s: 1.0e12\n  rotational_damping_per_s: 1.0e12\n"
                "  joint_damping_per_s: 1.0e12\n  damping_ratio_per_s: 1.0e12\n"
                "  task_frame_rad_per_s: 1.0e12\n"
                "passivity:\n  enabled: true\n  tank_initial_j: 1.0e5\n  tank_max_j: 1.0e6\n"
                "  nullspace_tank_initial_j: 1.0e5\n  nullspace_tank_max_j: 1.0e6\n"));
  expectSameTorques(reference, guarded, 2000);
  const PassivitySnapshot tank = guarded.diagnostics().passivity;
  EXPECT_GT(tank.injected_j, 0.0) << "the commands stiffened at an error: the tank paid";
  EXPECT_EQ(tank.refused_j, 0.0);
  EXPECT_NEAR(tank.gain_fraction, 1.0, 1e-9);
}

// ---- refill ----------------------------------------------------------------------------------

// The refill is computed from position increments: an arm that stands still while its velocity
// reads pure noise has dissipated nothing, and the tank must not be credited anything. (A refill
// computed from the measured velocity, dq^T D dq, would have credited D sigma^2 per second and
// joint: here 10 N m s/rad x (0.05 rad/s)^2 x 7 joints = 0.18 W.)
template <typename WrapperType>
void expectNoCreditFromVelocityNoise(WrapperType& wrapper) {
  JointState state = restingAt(wrapper.controller(), fr3Home());
  wrapper.activate(state);
  std::mt19937_64 random(7);
  std::normal_distribution<double> noise(0.0, 0.05);  // rad/s
  TorqueBuffer torque;
  for (int cycle = 0; cycle < 5000; ++cycle) {
    for (int joint = 0; joint < kFr3Dof; ++joint) {
      state.velocity[joint] = noise(random);
    }
    ASSERT_EQ(wrapper.update(state, kPeriod, torque.span()), CycleStatus::kOk);
  }
  const PassivitySnapshot tank = wrapper.diagnostics().passivity;
  // Zero up to the rounding of a rotation vector between two equal orientations (1e-17 rad).
  EXPECT_LT(tank.dissipated_j, 1e-12);
  EXPECT_NEAR(tank.tank_energy_j, 0.1, 1e-12);
}

TEST(GainGuard, VelocityNoiseOnAnArmAtRestCreditsTheTankNothing) {
  const std::string lines =
      "gain_ramps:\n  enabled: true\npassivity:\n  enabled: true\n  tank_initial_j: 0.1\n"
      "initial:\n  damping: 10.0\n";
  JointWrapper joint(fr3Config(kJointImpedancePlugin, lines));
  expectNoCreditFromVelocityNoise(joint);
  CartesianWrapper cartesian(
      fr3Config(kCartesianImpedancePlugin,
                "gain_ramps:\n  enabled: true\npassivity:\n  enabled: true\n  tank_initial_j: 0.1\n"
                "initial:\n  damping_ratio: 1.0\n"));
  expectNoCreditFromVelocityNoise(cartesian);
}

}  // namespace
}  // namespace comply::pipeline::test
