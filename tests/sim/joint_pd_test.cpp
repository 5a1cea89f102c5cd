// Output mode joint_pd (drives with an onboard PD, "MIT mode"). Every cycle, the drive's law at
// the sample, kp (q_d - q) + kd (dq_d - dq) + tau_ff, is the torque the same law gives in torque
// mode to 1e-9 N m: a second wrapper in torque mode runs beside it on the same states and
// commands. Then the PD-driven UR5e (its drives run the PD at 4 kHz, four physics substeps per
// control cycle) tracks a moving target like the torque-driven one.

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <string>

#include "output_modes/output_mode_rig.hpp"
#include "output_modes/output_modes_experiment.hpp"

namespace comply::testing {
namespace {

using experiments::kRigPeriodS;
using experiments::outputModeConfig;
using experiments::OutputModeRig;
using experiments::plantOf;

constexpr int kCycles = 3000;
constexpr double kRadiusM = 0.05;
constexpr double kFrequencyHz = 0.5;

/// The target of cycle `cycle`: a circle in the base y-z plane about `centre`, or a joint
/// reference swinging about `home`.
CartesianCommand targetAt(int cycle, const Eigen::Vector3d& centre,
                          const Eigen::Quaterniond& orientation, int dof) {
  const double t = cycle * kRigPeriodS;
  const double phase = 2.0 * M_PI * kFrequencyHz * t;
  CartesianCommand target = CartesianCommand::zero(dof);
  target.fields = CommandField::kPosition;
  target.stamp_s = t;
  target.position =
      centre + kRadiusM * Eigen::Vector3d(0.0, std::sin(phase), 1.0 - std::cos(phase));
  target.orientation = orientation;
  return target;
}

JointCommand targetAt(int cycle, const JointVector& home) {
  const double t = cycle * kRigPeriodS;
  JointCommand target = JointCommand::zero(static_cast<int>(home.size()));
  target.fields = CommandField::kPosition;
  target.stamp_s = t;
  target.position = home;
  target.position.array() += 0.2 * std::sin(2.0 * M_PI * kFrequencyHz * t);
  return target;
}

/// The drive's torque at the sample.
JointVector driveTorque(const ActuatorCommand& command, const JointState& state) {
  return command.stiffness.cwiseProduct(command.position - state.position) +
         command.damping.cwiseProduct(command.velocity - state.velocity) + command.effort;
}

template <typename Command>
void expectSplitIsExact(const pipeline::WrapperConfig& pd_config) {
  sim::PlantOptions options = plantOf(OutputMode::kJointPd);
  options.substeps = 4;
  OutputModeRig<Command> rig(pd_config, options);
  pipeline::WrapperConfig torque_config = pd_config;
  torque_config.output.mode = OutputMode::kTorque;
  pipeline::Wrapper<Command> torque_mode(torque_config);
  torque_mode.activate(rig.state);
  const int dof = rig.wrapper.dof();
  const MeasuredPose home = rig.wrapper.measuredPose();
  JointVector torque = JointVector::Zero(dof);
  double worst = 0.0;
  double largest_kp = 0.0;
  for (int cycle = 0; cycle < kCycles; ++cycle) {
    Command target;
    if constexpr (std::is_same_v<Command, CartesianCommand>) {
      target = targetAt(cycle, home.tcp_position, home.tcp_orientation, dof);
    } else {
      target = targetAt(cycle, home.position);
    }
    ASSERT_TRUE(rig.wrapper.submit(target).accepted);
    ASSERT_TRUE(torque_mode.submit(target).accepted);
    rig.read();
    ASSERT_TRUE(rig.wrapper.cycle(rig.state, kRigPeriodS, rig.command));
    ASSERT_EQ(torque_mode.update(rig.state, kRigPeriodS, {torque.data(), std::size_t(dof)}),
              pipeline::CycleStatus::kOk);
    ASSERT_TRUE(rig.plant.writeCommand(rig.command));
    rig.plant.step();
    worst = std::max(worst, (driveTorque(rig.command, rig.state) - torque).cwiseAbs().maxCoeff());
    largest_kp = std::max(largest_kp, rig.command.stiffness.maxCoeff());
  }
  EXPECT_LT(worst, 1e-9);
  EXPECT_GT(largest_kp, 1.0) << "the drive's PD carries the law's stiffness, not zero";
  std::printf("largest |kp (q_d - q) + kd (dq_d - dq) + tau_ff - tau| = %.2e N m\n", worst);
}

TEST(JointPd, TheDrivesLawAtTheSampleIsTheJointLawsTorque) {
  expectSplitIsExact<JointCommand>(outputModeConfig("ur5e", OutputMode::kJointPd, false));
}

TEST(JointPd, TheDrivesLawAtTheSampleIsTheCartesianLawsTorque) {
  pipeline::WrapperConfig config = outputModeConfig("ur5e", OutputMode::kJointPd);
  config.initial_cartesian.task_frame = experiments::identificationTaskFrame();
  expectSplitIsExact<CartesianCommand>(config);
}

/// RMS distance [m] of the plant's TCP from the circle's target over the run's last two periods.
double trackingRmsM(OutputMode mode) {
  const pipeline::WrapperConfig config = outputModeConfig("ur5e", mode);
  sim::PlantOptions options = plantOf(mode);
  options.substeps = 4;
  OutputModeRig<> rig(config, options);
  const MeasuredPose home = rig.wrapper.measuredPose();
  double squares = 0.0;
  int samples = 0;
  for (int cycle = 0; cycle < kCycles + 4000; ++cycle) {
    const CartesianCommand target =
        targetAt(cycle, home.tcp_position, home.tcp_orientation, rig.wrapper.dof());
    EXPECT_TRUE(rig.wrapper.submit(target).accepted);
    EXPECT_TRUE(rig.cycle()) << rig.wrapper.diagnostics().last_fault;
    if (cycle >= 3000) {
      // The pose after this cycle's step against the target it steered to.
      squares += (rig.plant.tcpPose().translation() - target.position).squaredNorm();
      ++samples;
    }
  }
  return std::sqrt(squares / samples);
}

TEST(JointPd, APdDrivenArmTracksLikeTheTorqueDrivenOne) {
  const double torque_rms = trackingRmsM(OutputMode::kTorque);
  const double pd_rms = trackingRmsM(OutputMode::kJointPd);
  std::printf("circle of 5 cm at 0.5 Hz, UR5e: RMS error torque %.2f mm, joint_pd %.2f mm\n",
              torque_rms * 1e3, pd_rms * 1e3);
  EXPECT_LT(pd_rms, 1.2 * torque_rms + 0.5e-3);
  EXPECT_GT(pd_rms, 0.8 * torque_rms - 0.5e-3);
}

}  // namespace
}  // namespace comply::testing
