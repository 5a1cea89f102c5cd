#pragma once
// A step of the TCP's orientation reference on the simulated arm at home, for the gain bound's
// torque-rate part (rate_limit_bound_test.cpp, rate_limit_sweep_test.cpp): what the torque-rate
// limit does with the swing after it.

#include <Eigen/Geometry>
#include <cstdint>
#include <string>

#include "comply/pipeline/gain_bound.hpp"
#include "comply/pipeline/wrapper.hpp"
#include "comply/sim/simulated_robot.hpp"

namespace comply::testing {

/// The rotational stiffness the torque-rate part allows [N m/rad]: the lightest rotational inertia
/// at the TCP x (R / tau)^2, R the lowest joint's rate limit.
inline double rotationalRateBound(const pipeline::GainBound& bound) {
  const double frequency = bound.torque_rate_limit.minCoeff() / bound.rate_limit_swing_nm;
  return bound.rotational_inertia_kg_m2 * frequency * frequency;
}

/// The rotational stiffness the sampled loop's part allows at 1 kHz [N m/rad].
inline double rotationalSampledBound(const pipeline::GainBound& bound) {
  const double frequency = bound.max_wn_period / 1e-3;
  return bound.rotational_inertia_kg_m2 * frequency * frequency;
}

struct TurnOutcome {
  bool accepted = false;  ///< the command with the stiffness and the step
  std::string refusal;
  std::uint64_t late_hits = 0;  ///< rate-limit hits (joint-cycles) in the last 0.5 s
  double late_ripple_nm = 0.0;  ///< the largest joint torque's peak to peak in the last 0.5 s
  bool faulted = false;
};

/// The arm at home under `config`; at 0.1 s the orientation reference steps by `step_rad` about
/// the TCP's `axis` (0, 1, 2: x, y, z) with rotational stiffness `stiffness` (critically damped),
/// then 1.9 s of holding.
inline TurnOutcome stepTurn(const pipeline::WrapperConfig& config, double stiffness,
                            double step_rad, int axis) {
  sim::SimulatedRobot plant(*config.robot_description, sim::PlantOptions{});
  pipeline::CartesianWrapper wrapper(config);
  const int dof = wrapper.dof();
  const auto size = static_cast<std::size_t>(dof);
  JointState state = JointState::zero(dof);
  plant.read(state);
  wrapper.activate(state);
  JointVector torque = JointVector::Zero(dof);
  JointVector lowest = JointVector::Constant(dof, 1e9);
  JointVector highest = JointVector::Constant(dof, -1e9);
  TurnOutcome outcome;
  std::uint64_t hits_before_tail = 0;
  constexpr int kStepCycle = 100;
  constexpr int kCycles = 2000;
  constexpr int kTail = 500;
  for (int cycle = 0; cycle < kCycles; ++cycle) {
    if (cycle == kStepCycle) {
      CartesianCommand command = CartesianCommand::zero(dof);
      command.stamp_s = 1.0;
      command.fields = CommandField::kPosition | CommandField::kStiffness | CommandField::kDamping;
      command.position = wrapper.measuredPose().tcp_position;
      command.orientation = wrapper.measuredPose().tcp_orientation *
                            Eigen::AngleAxisd(step_rad, Eigen::Vector3d::Unit(axis));
      command.stiffness_translational = 3000.0 * Eigen::Matrix3d::Identity();
      command.stiffness_rotational = stiffness * Eigen::Matrix3d::Identity();
      command.damping_mode = DampingMode::kRatio;
      command.damping_ratio.setOnes();
      const pipeline::Verdict verdict = wrapper.submit(command);
      outcome.accepted = verdict.accepted;
      outcome.refusal = verdict.message;
      if (!verdict.accepted) {
        return outcome;
      }
    }
    if (cycle == kCycles - kTail) {
      hits_before_tail = wrapper.diagnostics().rate_limit_hits;
    }
    plant.read(state);
    outcome.faulted =
        outcome.faulted || wrapper.update(state, plant.controlPeriod(), {torque.data(), size}) ==
                               pipeline::CycleStatus::kFault;
    plant.write({torque.data(), size});
    plant.step();
    if (cycle >= kCycles - kTail) {
      lowest = lowest.cwiseMin(torque);
      highest = highest.cwiseMax(torque);
    }
  }
  outcome.late_hits = wrapper.diagnostics().rate_limit_hits - hits_before_tail;
  outcome.late_ripple_nm = (highest - lowest).maxCoeff();
  return outcome;
}

}  // namespace comply::testing
