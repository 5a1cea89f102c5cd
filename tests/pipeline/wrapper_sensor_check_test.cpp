// The wrist sensor's checks (sensor_check.hpp) without a simulator: where the reading acts on the
// arm, the first reading at rest after activation must be near zero once the declared tool and
// the tare are off, or the cycle faults before the law runs, naming the declared and the measured
// mass; a failed check is made again at the reset; a tare and a reset pass it; the arm moving
// defers it; controllers whose sensor only reports are not checked; the comparison with the
// momentum observer faults only on a disagreement that lasts.

#include <gtest/gtest.h>

#include <string>

#include "comply/pipeline/sensor_check.hpp"
#include "comply/pipeline/wrapper.hpp"
#include "wrapper_support.hpp"

namespace comply::pipeline::test {
namespace {

constexpr double kToolKg = 1.2;
const Eigen::Vector3d kToolCom(0.0, 0.0, 0.05);  // tip frame [m]
const std::string kTool =
    "compensation:\n  payload:\n    enabled: true\n    mass_kg: 1.2\n    com_m: [0.0, 0.0, 0.05]\n";
const std::string kLimit = "force_control:\n  contact_force_limit_n: [0.0, 0.0, 20.0]\n";

/// What a sensor carrying `mass_kg` at kToolCom reads at `state`'s pose, plus `bias` (base
/// frame, force first).
Vector6d reading(const Controller& core, const JointState& state, double mass_kg,
                 const Vector6d& bias = Vector6d::Zero()) {
  model::Data data(core.model());
  const std::span<const double> q(state.position.data(), std::size_t(kFr3Dof));
  EXPECT_EQ(model::update(core.model(), data, q, q, model::Quantity::kPose),
            model::UpdateStatus::kOk);
  const Eigen::Vector3d weight = mass_kg * core.model().gravity();
  Vector6d raw;
  raw << weight, (data.tip_rotation * kToolCom).cross(weight);
  return raw + bias;
}

Vector6d forceAlongX(double newton) {
  Vector6d bias = Vector6d::Zero();
  bias[0] = newton;
  return bias;
}

/// The FR3 at home at rest, `wrench` read by its sensor.
JointState restingWith(const Controller& core, const Vector6d& wrench) {
  JointState state = restingAt(core, fr3Home());
  state.wrench = wrench;
  state.wrench_valid = true;
  return state;
}

TEST(WrapperSensorCheck, ADeclaredToolTheSensorDoesNotCarryFaultsBeforeTheLawRuns) {
  CartesianWrapper wrapper(fr3Config(kCartesianImpedancePlugin, kTool));
  const Controller& core = wrapper.controller();
  JointState state = restingAt(core, fr3Home());
  state.wrench = reading(core, state, 0.0);  // nothing mounted
  state.wrench_valid = true;
  wrapper.activate(state);
  TorqueBuffer torque;
  EXPECT_EQ(wrapper.update(state, kPeriod, torque.span()), CycleStatus::kFault);
  const std::string fault = wrapper.diagnostics().last_fault;
  EXPECT_NE(fault.find("wrist sensor: the declared tool (compensation.payload.mass_kg 1.20 kg)"),
            std::string::npos)
      << fault;
  EXPECT_NE(fault.find("0.00 kg along gravity"), std::string::npos) << fault;
  EXPECT_NE(fault.find("11.8 N"), std::string::npos) << "1.2 kg x 9.81 left: " << fault;

  // A reset with nothing changed checks again.
  wrapper.reset();
  EXPECT_EQ(wrapper.update(state, kPeriod, torque.span()), CycleStatus::kFault);
  EXPECT_EQ(wrapper.diagnostics().faults, 2U);

  // The tool mounted: the reset passes.
  state.wrench = reading(core, state, kToolKg);
  wrapper.reset();
  EXPECT_EQ(wrapper.update(state, kPeriod, torque.span()), CycleStatus::kOk);
  EXPECT_EQ(wrapper.diagnostics().state, WrapperState::kActive);
  EXPECT_LT(core.sensorWrench().norm(), 1e-9);
}

TEST(WrapperSensorCheck, TheMeasuredMassIsNamed) {
  CartesianWrapper wrapper(fr3Config(kCartesianImpedancePlugin, kTool));
  const Controller& core = wrapper.controller();
  JointState state = restingAt(core, fr3Home());
  state.wrench = reading(core, state, 2.0);  // a heavier tool than declared
  state.wrench_valid = true;
  wrapper.activate(state);
  TorqueBuffer torque;
  EXPECT_EQ(wrapper.update(state, kPeriod, torque.span()), CycleStatus::kFault);
  const std::string fault = wrapper.diagnostics().last_fault;
  EXPECT_NE(fault.find("mass_kg 1.20 kg"), std::string::npos) << fault;
  EXPECT_NE(fault.find("2.00 kg along gravity"), std::string::npos) << fault;
}

TEST(WrapperSensorCheck, AMassWithinTheToleranceActivates) {
  // 2 N plus 10 % of the tool's weight (1.18 N): a tool 0.3 kg heavier than declared passes.
  CartesianWrapper wrapper(fr3Config(kCartesianImpedancePlugin, kTool));
  const Controller& core = wrapper.controller();
  JointState state = restingAt(core, fr3Home());
  state.wrench = reading(core, state, kToolKg + 0.3);
  state.wrench_valid = true;
  wrapper.activate(state);
  TorqueBuffer torque;
  EXPECT_EQ(wrapper.update(state, kPeriod, torque.span()), CycleStatus::kOk);
  // Past the check, a reading is what the sensor feels: no FAULT on a later push.
  state.wrench = reading(core, state, kToolKg, forceAlongX(30.0));
  EXPECT_EQ(wrapper.update(state, kPeriod, torque.span()), CycleStatus::kOk);
}

TEST(WrapperSensorCheck, ATareInFaultAndAResetPassABias) {
  CartesianWrapper wrapper(fr3Config(kCartesianImpedancePlugin, kTool));
  const Controller& core = wrapper.controller();
  JointState state = restingAt(core, fr3Home());
  state.wrench = reading(core, state, kToolKg, forceAlongX(5.0));  // the sensor's own offset
  state.wrench_valid = true;
  wrapper.activate(state);
  TorqueBuffer torque;
  EXPECT_EQ(wrapper.update(state, kPeriod, torque.span()), CycleStatus::kFault);
  EXPECT_NE(wrapper.diagnostics().last_fault.find("1.20 kg along gravity"), std::string::npos)
      << "the bias is across gravity: " << wrapper.diagnostics().last_fault;
  ASSERT_EQ(wrapper.tare(), "");
  EXPECT_EQ(wrapper.update(state, kPeriod, torque.span()), CycleStatus::kFault);
  wrapper.reset();
  EXPECT_EQ(wrapper.update(state, kPeriod, torque.span()), CycleStatus::kOk);
  EXPECT_LT(core.sensorWrench().norm(), 1e-9);
}

TEST(WrapperSensorCheck, TheCheckWaitsForTheArmAtRest) {
  CartesianWrapper wrapper(fr3Config(kCartesianImpedancePlugin, kTool));
  const Controller& core = wrapper.controller();
  JointState state = restingAt(core, fr3Home());
  state.wrench = reading(core, state, 0.0);
  state.wrench_valid = true;
  state.velocity[3] = 2.0 * SensorCheck::kRestSpeedRadPerS;  // the tool's inertia is in the reading
  wrapper.activate(state);
  TorqueBuffer torque;
  for (int cycle = 0; cycle < 10; ++cycle) {
    ASSERT_EQ(wrapper.update(state, kPeriod, torque.span()), CycleStatus::kOk);
  }
  state.velocity.setZero();
  EXPECT_EQ(wrapper.update(state, kPeriod, torque.span()), CycleStatus::kFault);
}

TEST(WrapperSensorCheck, OnceItPassedAReadingIsAContact) {
  CartesianWrapper wrapper(fr3Config(kCartesianImpedancePlugin, kLimit));
  const Controller& core = wrapper.controller();
  JointState state = restingWith(core, Vector6d::Zero());
  wrapper.activate(state);
  TorqueBuffer torque;
  ASSERT_EQ(wrapper.update(state, kPeriod, torque.span()), CycleStatus::kOk);
  state.wrench = forceAlongX(15.0);
  for (int cycle = 0; cycle < 100; ++cycle) {
    ASSERT_EQ(wrapper.update(state, kPeriod, torque.span()), CycleStatus::kOk);
  }
  // A reactivation checks again: the push is still there.
  wrapper.deactivate();
  wrapper.activate(state);
  EXPECT_EQ(wrapper.update(state, kPeriod, torque.span()), CycleStatus::kFault);
  EXPECT_NE(wrapper.diagnostics().last_fault.find("the reading at rest is 15.0 N"),
            std::string::npos)
      << wrapper.diagnostics().last_fault;
}

/// The first cycle's status of `config` at home with the sensor reading a 5 N bias along x.
template <typename Wrapper = CartesianWrapper>
CycleStatus firstCycleWithABias(const WrapperConfig& config) {
  Wrapper wrapper(config);
  JointState state = restingWith(wrapper.controller(), forceAlongX(5.0));
  wrapper.activate(state);
  TorqueBuffer torque;
  return wrapper.update(state, kPeriod, torque.span());
}

TEST(WrapperSensorCheck, ItAppliesWhereTheReadingActsOnTheArm) {
  // A contact-force limit read from the sensor: checked.
  EXPECT_EQ(firstCycleWithABias(fr3Config(kCartesianImpedancePlugin, kLimit)), CycleStatus::kFault);
  EXPECT_EQ(firstCycleWithABias(fr3Config(
                kCartesianImpedancePlugin,
                "force_control:\n  source: sensor\n  contact_torque_limit_n_m: [0.0, 0.0, 2.0]\n"
                "observer:\n  enabled: true\n")),
            CycleStatus::kFault);
  // The tolerance is the file's.
  EXPECT_EQ(
      firstCycleWithABias(fr3Config(kCartesianImpedancePlugin,
                                    kLimit + "wrench_sensor:\n  rest_force_tolerance_n: 6.0\n")),
      CycleStatus::kOk);
  // The sensor only reported (no tool, no limit): tared when the user chooses, not checked.
  EXPECT_EQ(firstCycleWithABias(fr3Config(kCartesianImpedancePlugin)), CycleStatus::kOk);
  // The limit read from the observer: the sensor does not act on the arm.
  EXPECT_EQ(firstCycleWithABias(
                fr3Config(kCartesianImpedancePlugin, kLimit + "observer:\n  enabled: true\n")),
            CycleStatus::kOk);
  // A joint law has no contact-force limit; a declared tool is checked all the same.
  EXPECT_EQ(firstCycleWithABias<JointWrapper>(fr3Config(kJointImpedancePlugin)), CycleStatus::kOk);
  EXPECT_EQ(firstCycleWithABias<JointWrapper>(fr3Config(kJointImpedancePlugin, kTool)),
            CycleStatus::kFault);
}

TEST(SensorCheck, TheObserverComparisonFaultsOnADisagreementThatLasts) {
  const auto resolved = resolveController(
      fr3Config(kCartesianImpedancePlugin,
                "observer:\n  enabled: true\nwrench_sensor:\n  observer_tolerance_n: 3.0\n"));
  SensorCheck check(*resolved);
  ASSERT_TRUE(check.comparesWithObserver());
  EXPECT_FALSE(check.checksAtRest()) << "no tool, no limit on the sensor, no admittance";
  Vector6d sensor = Vector6d::Zero();
  sensor[2] = 10.0;
  Vector6d observer = sensor;
  // Both from zero, the observer as its residual rises: the sensor's filter follows the same way.
  Vector6d rising = Vector6d::Zero();
  for (int cycle = 0; cycle < 1000; ++cycle) {
    rising += (1.0 - std::exp(-50.0 * kPeriod)) * (observer - rising);
    ASSERT_TRUE(check.compareWithObserver(sensor, rising, kPeriod)) << cycle;
  }
  // A disagreement of 5 N for 50 ms, then none: no FAULT.
  observer[2] = 5.0;
  for (int cycle = 0; cycle < 50; ++cycle) {
    ASSERT_TRUE(check.compareWithObserver(sensor, observer, kPeriod)) << cycle;
  }
  observer[2] = 10.0;
  ASSERT_TRUE(check.compareWithObserver(sensor, observer, kPeriod));
  // The same, lasting: a FAULT after 0.1 s.
  observer[2] = 5.0;
  int cycles = 0;
  while (check.compareWithObserver(sensor, observer, kPeriod) && cycles < 1000) {
    ++cycles;
  }
  EXPECT_NEAR(cycles, 100, 1);
  const std::string detail = check.detail();
  EXPECT_NE(detail.find("differ by 5.0 N"), std::string::npos) << detail;
  EXPECT_NE(detail.find("observer_tolerance_n 3"), std::string::npos) << detail;
}

TEST(SensorCheck, AResetInContactComparesFromTheObserversEstimate) {
  // A slow observer (5/s): a filter started from zero would trail the 10 N it reads by more than
  // the tolerance for 0.24 s.
  const auto resolved =
      resolveController(fr3Config(kCartesianImpedancePlugin,
                                  "observer:\n  enabled: true\n  gain_per_s: 5\n"
                                  "wrench_sensor:\n  observer_tolerance_n: 3.0\n"));
  SensorCheck check(*resolved);
  Vector6d sensor = Vector6d::Zero();
  sensor[2] = 10.0;
  // In contact a while: the observer and the filter both at 10 N.
  for (int cycle = 0; cycle < 3000; ++cycle) {
    Vector6d observer = sensor * (1.0 - std::exp(-5.0 * kPeriod * (cycle + 1)));
    ASSERT_TRUE(check.compareWithObserver(sensor, observer, kPeriod)) << cycle;
  }
  // A reset: the observer keeps its estimate (it is reset only at activation), and the
  // comparison starts again from it: no FAULT while both read 10 N.
  check.restart();
  for (int cycle = 0; cycle < 1000; ++cycle) {
    ASSERT_TRUE(check.compareWithObserver(sensor, sensor, kPeriod)) << cycle;
  }
}

}  // namespace
}  // namespace comply::pipeline::test
