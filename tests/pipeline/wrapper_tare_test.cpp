// The wrist sensor's path through the cycle without a simulator: the declared tool's weight comes
// off the reading at its centre of mass in every pose; a tare takes what remains as the zero,
// kept in the TCP frame so that it turns with the sensor; a tare without any reading is refused.

#include <gtest/gtest.h>

#include <cmath>

#include "comply/pipeline/wrapper.hpp"
#include "wrapper_support.hpp"

namespace comply::pipeline::test {
namespace {

constexpr double kToolKg = 1.2;
const Eigen::Vector3d kToolCom(0.01, -0.02, 0.07);  // tip frame [m]

/// What a sensor under the tool reads at `state`'s pose: the tool's weight at its centre of mass
/// plus `offset_in_tcp`, base frame, about the TCP.
Vector6d rawReading(const Controller& core, const JointState& state,
                    const Vector6d& offset_in_tcp) {
  model::Data data(core.model());
  const std::span<const double> q(state.position.data(), std::size_t(kFr3Dof));
  EXPECT_EQ(model::update(core.model(), data, q, q, model::Quantity::kPose),
            model::UpdateStatus::kOk);
  const Eigen::Vector3d weight = kToolKg * core.model().gravity();
  const Eigen::Vector3d arm = data.tip_rotation * kToolCom;
  Vector6d raw;
  raw << weight + data.tip_rotation * offset_in_tcp.head<3>(),
      arm.cross(weight) + data.tip_rotation * offset_in_tcp.tail<3>();
  return raw;
}

TEST(WrapperTare, TheToolsWeightAndTheTareComeOffInEveryPose) {
  // The sensor's offset (3.7 N) is tared after activation: the rest check, which would fault on
  // it (wrapper_sensor_check_test.cpp), is given room.
  CartesianWrapper wrapper(fr3Config(kCartesianImpedancePlugin,
                                     "compensation:\n  payload:\n    enabled: true\n"
                                     "    mass_kg: 1.2\n    com_m: [0.01, -0.02, 0.07]\n"
                                     "wrench_sensor:\n  rest_force_tolerance_n: 5.0\n"
                                     "  rest_torque_tolerance_n_m: 1.0\n"));
  EXPECT_EQ(wrapper.tare(),
            "the hardware has given no wrist force/torque reading: nothing to tare");
  const Controller& core = wrapper.controller();
  Vector6d sensor_offset;
  sensor_offset << 1.0, -2.0, 3.0, 0.1, 0.2, -0.3;
  JointState state = restingAt(core, fr3Home());
  state.wrench = rawReading(core, state, sensor_offset);
  state.wrench_valid = true;
  wrapper.activate(state);
  TorqueBuffer torque;
  ASSERT_EQ(wrapper.update(state, kPeriod, torque.span()), CycleStatus::kOk);
  ASSERT_TRUE(core.sensorWrenchValid());
  // The tool's weight is off: what is left is the offset, in the base frame.
  EXPECT_NEAR((core.sensorWrench() - rawReading(core, state, sensor_offset)).head<3>().norm(),
              kToolKg * 9.81, 1e-6);
  EXPECT_GT(core.sensorWrench().head<3>().norm(), 3.0);

  ASSERT_EQ(wrapper.tare(), "");
  ASSERT_EQ(wrapper.update(state, kPeriod, torque.span()), CycleStatus::kOk);
  EXPECT_LT(core.sensorWrench().norm(), 1e-9);

  // Another pose, the wrist turned: tool weight and offset both turned with it; still zero.
  const JointVector turned = offset(offset(fr3Home(), 6, 1.2), 5, -0.4);
  JointState moved = restingAt(core, turned);
  moved.wrench = rawReading(core, moved, sensor_offset);
  moved.wrench_valid = true;
  ASSERT_EQ(wrapper.update(moved, kPeriod, torque.span()), CycleStatus::kOk);
  EXPECT_LT(core.sensorWrench().norm(), 1e-9) << core.sensorWrench().transpose();

  // A push on top reads as the push.
  Vector6d push;
  push << 4.0, 0.5, -6.0, 0.3, 0.0, 0.1;
  moved.wrench += push;
  ASSERT_EQ(wrapper.update(moved, kPeriod, torque.span()), CycleStatus::kOk);
  EXPECT_LT((core.sensorWrench() - push).norm(), 1e-9);

  // A cycle without a reading: not valid, and a tare then keeps the zero in force.
  moved.wrench_valid = false;
  ASSERT_EQ(wrapper.tare(), "") << "the hardware has given readings before";
  ASSERT_EQ(wrapper.update(moved, kPeriod, torque.span()), CycleStatus::kOk);
  EXPECT_FALSE(core.sensorWrenchValid());
  moved.wrench_valid = true;
  ASSERT_EQ(wrapper.update(moved, kPeriod, torque.span()), CycleStatus::kOk);
  EXPECT_LT((core.sensorWrench() - push).norm(), 1e-9);
}

TEST(WrapperTare, TheLowPassFollowsAStepWithItsTimeConstant) {
  CartesianWrapper wrapper(
      fr3Config(kCartesianImpedancePlugin, "wrench_sensor:\n  filter_hz: 10.0\n"));
  const Controller& core = wrapper.controller();
  JointState state = restingAt(core, fr3Home());
  state.wrench.setZero();
  state.wrench_valid = true;
  wrapper.activate(state);
  TorqueBuffer torque;
  ASSERT_EQ(wrapper.update(state, kPeriod, torque.span()), CycleStatus::kOk);
  EXPECT_LT(core.sensorWrench().norm(), 1e-12);
  state.wrench[2] = -10.0;  // a step of 10 N down
  const double time_constant_s = 1.0 / (2.0 * M_PI * 10.0);
  int cycles = 0;
  while (core.sensorWrench()[2] > -10.0 * (1.0 - std::exp(-1.0)) && cycles < 1000) {
    ASSERT_EQ(wrapper.update(state, kPeriod, torque.span()), CycleStatus::kOk);
    ++cycles;
  }
  EXPECT_NEAR(cycles * kPeriod, time_constant_s, 0.1 * time_constant_s);
  for (int i = 0; i < 200; ++i) {
    ASSERT_EQ(wrapper.update(state, kPeriod, torque.span()), CycleStatus::kOk);
  }
  EXPECT_NEAR(core.sensorWrench()[2], -10.0, 1e-3) << "settled on the reading";
}

TEST(WrapperTare, AReadingInTheTcpFrameIsTurnedIntoTheBase) {
  CartesianWrapper wrapper(fr3Config(kCartesianImpedancePlugin));
  const Controller& core = wrapper.controller();
  JointState state = restingAt(core, offset(fr3Home(), 6, 0.7));
  Vector6d in_base;
  in_base << 4.0, -2.0, 7.0, 0.3, -0.1, 0.2;
  state.wrench_valid = true;
  wrapper.activate(state);
  const Eigen::Matrix3d tcp = core.modelData().tip_rotation;
  ASSERT_FALSE(tcp.isApprox(Eigen::Matrix3d::Identity(), 1e-3)) << "a turned TCP shows the turn";
  state.wrench << tcp.transpose() * in_base.head<3>(), tcp.transpose() * in_base.tail<3>();
  state.wrench_in_tcp = true;  // as a ros2_control force-torque sensor reports it
  TorqueBuffer torque;
  ASSERT_EQ(wrapper.update(state, kPeriod, torque.span()), CycleStatus::kOk);
  EXPECT_LT((core.sensorWrench() - in_base).norm(), 1e-12) << core.sensorWrench().transpose();
}

}  // namespace
}  // namespace comply::pipeline::test
