// The momentum observer against known wrenches on all four robots: a wrench applied at the TCP in
// MuJoCo (xfrc_applied, the simulator's own Jacobians) while the Cartesian impedance holds the
// arm. After it settles the estimate is within 5 % + 0.5 N (5 % + 0.05 N m) of the applied
// wrench, and its step response has the time constant 1/K_O within 20 %. A golden check then
// recomputes r(t) from the same logged q, dq and tau with an independent dynamics model (KDL's
// mass matrix, Coriolis and gravity) and the formula written out here.
//
// The plant runs without robot.yaml's Coulomb friction, an external torque to an observer given
// the commanded torque (an arm with joint-torque sensing removes it with
// observer.measured_torque). Its joint damping and rotor armature stay: without them the smallest
// wrist joints cannot be held stably at 1 kHz. The model's M(q) carries the same rotor inertias
// (robot.yaml), so in motion only the damping shows (damping times velocity); a model without them
// sees the armature's torque (armature times acceleration) as external while the arm accelerates.

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <memory>
#include <string>
#include <vector>

#include "comply/host/state_sample.hpp"
#include "comply/model/robot_description.hpp"
#include "comply/pipeline/wrapper.hpp"
#include "comply/sim/simulated_robot.hpp"
#include "kdl_reference.hpp"
#include "sim_support.hpp"

namespace comply::testing {
namespace {

constexpr double kGainPerS = 50.0;  // K_O: time constant 20 ms
constexpr double kPeriodS = 0.001;
constexpr int kStepCycle = 300;  // the wrench is applied from here
constexpr int kCycles = 1500;    // 1.2 s after it: the arm has settled

struct Logged {
  std::vector<JointVector> position, velocity, torque;  // per cycle: state and torque applied
  std::vector<JointVector> residual;                    // the wrapper's r after that cycle
  std::vector<Vector6d> wrench;                         // the wrapper's wrench after that cycle
  host::StateSample last;  // the state a host reports after the last cycle
};

/// The task frame of the runs: turned, so that the state's task-frame wrench differs from the
/// base frame's.
const Eigen::Quaterniond kTaskFrame(Eigen::AngleAxisd(0.5, Eigen::Vector3d::UnitZ()));

/// Whether the controller's model knows the plant's rotor armature.
enum class Armature { kKnown, kUnknownToTheModel };

void runWithWrench(const std::string& robot, const Vector6d& applied, Logged& log,
                   Armature armature = Armature::kKnown) {
  pipeline::WrapperConfig config = simCartesianConfig(robot);
  config.observer.enabled = true;
  config.observer.gain_per_s = kGainPerS;
  config.initial_cartesian.task_frame = kTaskFrame;
  sim::PlantOptions plant_options;
  plant_options.friction_scale = 0.0;
  sim::SimulatedRobot plant(*config.robot_description, plant_options);
  if (armature == Armature::kUnknownToTheModel) {
    auto bare = std::make_shared<model::RobotDescription>(*config.robot_description);
    std::fill(bare->joint_dynamics->armature.begin(), bare->joint_dynamics->armature.end(), 0.0);
    config.robot_description = bare;
  }
  pipeline::CartesianWrapper wrapper(config);
  const int dof = wrapper.dof();
  JointState state = JointState::zero(dof);
  plant.read(state);
  wrapper.activate(state);
  JointVector torque = JointVector::Zero(dof);
  for (int cycle = 0; cycle < kCycles; ++cycle) {
    if (cycle == kStepCycle) {
      plant.setExternalWrench(applied);
    }
    plant.read(state);
    ASSERT_NE(wrapper.update(state, kPeriodS, {torque.data(), static_cast<std::size_t>(dof)}),
              pipeline::CycleStatus::kFault)
        << "cycle " << cycle << ": " << wrapper.diagnostics().last_fault;
    plant.write({torque.data(), static_cast<std::size_t>(dof)});
    plant.step();
    log.position.push_back(state.position);
    log.velocity.push_back(state.velocity);
    log.torque.push_back(state.effort);  // the plant reports the torque it applied
    log.residual.push_back(wrapper.controller().observer().jointTorque());
    log.wrench.push_back(wrapper.controller().observer().wrench());
  }
  host::StateSampler<CartesianCommand> sampler(wrapper);
  hardware::CycleRecord record;
  record.index = kCycles - 1;
  record.wrote = true;
  record.state = &state;
  record.torque = {torque.data(), static_cast<std::size_t>(dof)};
  sampler.fill(record, state, transport::Stamp{}, log.last);
}

/// The mean estimate over the last 100 ms, held to 5 % + 0.5 N and 5 % + 0.05 N m of `applied`.
Vector6d expectSettledOn(const Logged& log, const Vector6d& applied) {
  Vector6d settled = Vector6d::Zero();
  for (int cycle = kCycles - 100; cycle < kCycles; ++cycle) {
    settled += log.wrench[cycle] / 100.0;
  }
  const double force_error = (settled.head<3>() - applied.head<3>()).norm();
  const double torque_error = (settled.tail<3>() - applied.tail<3>()).norm();
  EXPECT_LT(force_error, 0.05 * applied.head<3>().norm() + 0.5) << settled.transpose();
  EXPECT_LT(torque_error, 0.05 * applied.tail<3>().norm() + 0.05) << settled.transpose();
  // Before the push: nothing (the observer does not see the arm's own dynamics).
  EXPECT_LT(log.wrench[kStepCycle - 1].head<3>().norm(), 0.5);
  ::testing::Test::RecordProperty("force_error_n", std::to_string(force_error));
  ::testing::Test::RecordProperty("torque_error_nm", std::to_string(torque_error));
  return settled;
}

class MomentumObserver : public ::testing::TestWithParam<std::string> {};

TEST_P(MomentumObserver, EstimatesAKnownWrenchWithItsTimeConstant) {
  Vector6d applied;
  applied << 12.0, -8.0, 15.0, 0.6, -0.4, 0.5;  // [N, N m] base frame, about the TCP
  Logged log;
  runWithWrench(GetParam(), applied, log);
  ASSERT_EQ(log.wrench.size(), static_cast<std::size_t>(kCycles));

  // The plant's inertia is the model's, rotors included: the estimate is the applied wrench
  // filtered by 1/K_O, nothing else.
  const Vector6d settled = expectSettledOn(log, applied);

  // Step response along the applied force: 63 % after about 1/K_O.
  const Eigen::Vector3d direction = applied.head<3>().normalized();
  const double final_value = settled.head<3>().dot(direction);
  int reached = -1;
  for (int cycle = kStepCycle; cycle < kCycles && reached < 0; ++cycle) {
    if (log.wrench[cycle].head<3>().dot(direction) >= (1.0 - std::exp(-1.0)) * final_value) {
      reached = cycle;
    }
  }
  ASSERT_GT(reached, 0);
  // The wrench acts from the step after cycle kStepCycle's update: the estimate of cycle k has
  // seen k - kStepCycle steps of it.
  const double time_constant_s = (reached - kStepCycle) * kPeriodS;
  EXPECT_NEAR(time_constant_s, 1.0 / kGainPerS, 0.2 / kGainPerS);
  RecordProperty("time_constant_ms", std::to_string(time_constant_s * 1e3));

  // What a host reports: the estimate, named as such, in the base, TCP and task frames.
  const host::StateSample& state = log.last;
  EXPECT_EQ(state.contact_wrench_source, transport::WrenchSource::kObserver);
  EXPECT_TRUE(state.contact_wrench.isApprox(log.wrench.back(), 1e-12));
  const Eigen::Matrix3d tcp = state.tcp_orientation.toRotationMatrix();
  const Eigen::Matrix3d task = kTaskFrame.toRotationMatrix();
  EXPECT_LT((tcp * state.contact_wrench_tcp.head<3>() - state.contact_wrench.head<3>()).norm(),
            1e-9);
  EXPECT_LT((tcp * state.contact_wrench_tcp.tail<3>() - state.contact_wrench.tail<3>()).norm(),
            1e-9);
  EXPECT_LT((task * state.contact_wrench_task.head<3>() - state.contact_wrench.head<3>()).norm(),
            1e-9);
  EXPECT_LT((task * state.contact_wrench_task.tail<3>() - state.contact_wrench.tail<3>()).norm(),
            1e-9);
  EXPECT_GT((state.contact_wrench_task - state.contact_wrench).norm(), 1.0);  // the frame turned
}

// With an armature the model does not know of (a robot.yaml that declares none): wrong only while
// the arm accelerates, right once it is still.
TEST_P(MomentumObserver, ArmatureDoesNotBiasTheSettledEstimate) {
  Vector6d applied;
  applied << -9.0, 14.0, -11.0, -0.3, 0.7, 0.2;
  Logged log;
  runWithWrench(GetParam(), applied, log, Armature::kUnknownToTheModel);
  ASSERT_EQ(log.wrench.size(), static_cast<std::size_t>(kCycles));
  expectSettledOn(log, applied);
}

// r(t) from the logged q, dq and tau with KDL's dynamics and the discrete law written out again:
// the wrapper's residual, cycle for cycle.
TEST_P(MomentumObserver, ResidualMatchesAnIndependentComputation) {
  Vector6d applied;
  applied << -6.0, 10.0, -4.0, 0.2, 0.3, -0.1;
  Logged log;
  runWithWrench(GetParam(), applied, log);
  ASSERT_EQ(log.wrench.size(), static_cast<std::size_t>(kCycles));
  const model::RobotDescription robot = model::loadRobotDescription(GetParam());
  const KdlReference kdl(robot.urdf_path.string(), robot.base_frame, robot.tcp_frame, robot.joints);
  const int dof = static_cast<int>(log.position.front().size());
  Eigen::VectorXd momentum0, integral = Eigen::VectorXd::Zero(dof), r = Eigen::VectorXd::Zero(dof);
  Eigen::MatrixXd previous_mass;
  double worst = 0.0;
  double largest = 0.0;
  for (std::size_t k = 0; k < log.position.size(); ++k) {
    const Eigen::VectorXd q = log.position[k];
    const Eigen::VectorXd dq = log.velocity[k];
    ReferenceResult reference = kdl.compute(q, dq);
    // The controller's M(q) is the links' plus the rotor inertias robot.yaml declares.
    for (int i = 0; i < dof; ++i) {
      reference.mass_matrix(i, i) += robot.joint_dynamics->armature[static_cast<std::size_t>(i)];
    }
    const Eigen::MatrixXd& mass = reference.mass_matrix;
    if (k == 0) {
      momentum0 = mass * dq;
      previous_mass = mass;
      continue;
    }
    // The torque over the period that ended is what the plant applied in it (logged at k - 1's
    // write, read back at k).
    const Eigen::VectorXd tau = log.torque[k];
    const Eigen::VectorXd coriolis_transposed =
        (mass - previous_mass) * dq / kPeriodS - reference.coriolis;
    integral += kPeriodS * (tau + coriolis_transposed - reference.gravity + r);
    r = kGainPerS * (mass * dq - momentum0 - integral);
    previous_mass = mass;
    worst = std::max(worst, (r - Eigen::VectorXd(log.residual[k])).cwiseAbs().maxCoeff());
    largest = std::max(largest, r.cwiseAbs().maxCoeff());
  }
  EXPECT_GT(largest, 1.0);  // the push shows in r
  EXPECT_LT(worst, 1e-6 * std::max(largest, 1.0)) << "largest |r| " << largest;
}

INSTANTIATE_TEST_SUITE_P(Robots, MomentumObserver, ::testing::ValuesIn(model::availableRobots()),
                         [](const auto& test) { return test.param; });

}  // namespace
}  // namespace comply::testing
