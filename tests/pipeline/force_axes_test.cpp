// The force stage on its own (force_axes.hpp), at the FR3's home pose with a task frame turned
// away from the base: along a force axis the spring is out (reference on the measured pose, rates
// zero) and the PI push is in the feedforward; its integral is bounded and frozen while the speed
// bound acts; the contact-force limit pulls an impedance axis's reference back at the stated rate
// and returns it; rotational axes behave the same way.

#include "comply/pipeline/force_axes.hpp"

#include <gtest/gtest.h>

#include <cmath>

#include "comply/core/rotation.hpp"
#include "comply/pipeline/wrapper.hpp"
#include "comply/schema/schema.hpp"
#include "wrapper_support.hpp"

namespace comply::pipeline::test {
namespace {

using Eigen::Map;
using Eigen::Vector3d;

constexpr double kStiffness = 800.0;  // N/m on every translational axis

class ForceAxesTest : public ::testing::Test {
 protected:
  void SetUp() override {
    const Controller& core = wrapper_.controller();
    const JointVector q = fr3Home();
    const std::span<const double> joints(q.data(), std::size_t(kFr3Dof));
    ASSERT_EQ(model::update(core.model(), data_, joints, joints, model::Quantity::kPose),
              model::UpdateStatus::kOk);
    task_ = Eigen::Quaterniond(Eigen::AngleAxisd(0.5, Vector3d::UnitZ()) *
                               Eigen::AngleAxisd(0.4, Vector3d::UnitX()));
    CartesianCommand command = CartesianCommand::zero(kFr3Dof);
    // Reference 2 cm and 0.1 rad away from the measured pose along base axes.
    command.position = data_.tip_position + Vector3d(0.02, -0.01, 0.015);
    command.orientation =
        Eigen::AngleAxisd(0.1, Vector3d(1, 2, 3).normalized()) * data_.tip_orientation;
    command.twist << 0.1, 0.2, 0.3, 0.4, 0.5, 0.6;
    command.acceleration << 1, 2, 3, 4, 5, 6;
    command.wrench_feedforward << 1.0, 2.0, 3.0, 0.1, 0.2, 0.3;
    command.stiffness_translational = kStiffness * Eigen::Matrix3d::Identity();
    command.stiffness_rotational = 40.0 * Eigen::Matrix3d::Identity();
    command.task_frame = task_;
    in_ = schema::toBus(command, kFr3Dof);
  }

  /// A base-frame 6-vector of a bus, in the task frame.
  [[nodiscard]] Vector6d inTask(const double* base) const {
    const Eigen::Matrix3d r = task_.toRotationMatrix();
    Vector6d task;
    task << r.transpose() * Map<const Vector3d>(base),
        r.transpose() * Map<const Vector3d>(base + 3);
    return task;
  }
  /// The pose error (reference - measured) of a bus, in the task frame.
  [[nodiscard]] Vector6d errorInTask(const comply_cartesian_command& bus) const {
    const Eigen::Matrix3d r = task_.toRotationMatrix();
    Vector6d error;
    error << r.transpose() * (Map<const Vector3d>(bus.position) - data_.tip_position),
        r.transpose() * orientationError(data_.tip_orientation, schema::fromXyzw(bus.orientation));
    return error;
  }
  /// A wrench the TCP exerts, given in the task frame, as the environment's wrench on the tool in
  /// the base frame (what the stage reads).
  [[nodiscard]] Vector6d onTool(const Vector6d& exerted_in_task) const {
    const Eigen::Matrix3d r = task_.toRotationMatrix();
    Vector6d base;
    base << -(r * exerted_in_task.head<3>()), -(r * exerted_in_task.tail<3>());
    return base;
  }
  /// A TCP twist given in the task frame, in the base frame.
  [[nodiscard]] Vector6d twistFromTask(const Vector6d& task_twist) const {
    const Eigen::Matrix3d r = task_.toRotationMatrix();
    Vector6d base;
    base << r * task_twist.head<3>(), r * task_twist.tail<3>();
    return base;
  }

  CartesianWrapper wrapper_{fr3Config(kCartesianImpedancePlugin)};
  model::Data data_{wrapper_.controller().model()};
  Eigen::Quaterniond task_;
  comply_cartesian_command in_{};
  comply_cartesian_command out_{};
  ForceAxes stage_;
};

TEST_F(ForceAxesTest, WithoutAxesOrLimitsTheStageStandsAside) {
  stage_.configure(ForceControlConfig{});
  EXPECT_FALSE(stage_.acts(in_));
  in_.force_axes[5] = 1.0;
  EXPECT_TRUE(stage_.acts(in_));
  ForceControlConfig limited;
  limited.contact_force_limit_n = Vector3d(0.0, 0.0, 30.0);
  in_.force_axes[5] = 0.0;
  stage_.configure(limited);
  EXPECT_TRUE(stage_.acts(in_));
}

TEST_F(ForceAxesTest, AForceAxisLosesItsSpringAndPushesTheTarget) {
  stage_.configure({.proportional_gain = 0.5, .integral_gain_per_s = 5.0});
  in_.force_axes[2] = 1.0;  // task z
  in_.wrench_target[2] = 10.0;
  const Vector6d exerted = (Vector6d() << 1.0, 2.0, 6.0, 0.1, 0.2, 0.3).finished();
  const Vector6d wrench = onTool(exerted);
  stage_.apply(in_, data_, Vector6d::Zero(), &wrench, kPeriod, out_);

  const Vector6d error_in = errorInTask(in_);
  const Vector6d error_out = errorInTask(out_);
  EXPECT_NEAR(error_out[2], 0.0, 1e-12) << "the spring along the force axis is out";
  for (const int axis : {0, 1, 3, 4, 5}) {
    EXPECT_NEAR(error_out[axis], error_in[axis], 1e-12) << "axis " << axis << " stays impedance";
  }
  EXPECT_NEAR(inTask(out_.twist)[2], 0.0, 1e-12);
  EXPECT_NEAR(inTask(out_.acceleration)[2], 0.0, 1e-12);
  EXPECT_NEAR(inTask(out_.twist)[0], inTask(in_.twist)[0], 1e-12);
  EXPECT_NEAR(inTask(out_.acceleration)[4], inTask(in_.acceleration)[4], 1e-12);
  // First cycle: F_d + k_p (F_d - F) + k_i (F_d - F) dt on top of the command's feedforward.
  const double push = 10.0 + 0.5 * 4.0 + 5.0 * 4.0 * kPeriod;
  Vector6d added = inTask(out_.wrench_feedforward) - inTask(in_.wrench_feedforward);
  EXPECT_NEAR(added[2], push, 1e-9);
  EXPECT_NEAR(stage_.forceCommand()[2], push, 1e-12);
  added[2] = 0.0;
  EXPECT_LT(added.norm(), 1e-12) << "nothing added along the impedance axes";
  for (const double axis : out_.force_axes) {
    EXPECT_EQ(axis, 0.0) << "the law reads no force axes: the stage has done them";
  }
  // The orientation reference is untouched (no rotational axis selected).
  EXPECT_EQ(schema::fromXyzw(out_.orientation).coeffs(),
            schema::fromXyzw(in_.orientation).coeffs());
}

TEST_F(ForceAxesTest, TheIntegralIsBoundedAndHoldsWithoutAnEstimate) {
  stage_.configure(
      {.proportional_gain = 0.0, .integral_gain_per_s = 10.0, .integral_limit_n = 3.0});
  in_.force_axes[1] = 1.0;
  in_.wrench_target[1] = -8.0;                       // pull along -y of the task frame
  const Vector6d wrench = onTool(Vector6d::Zero());  // no contact: error -8 N
  for (int cycle = 0; cycle < 20; ++cycle) {
    stage_.apply(in_, data_, Vector6d::Zero(), &wrench, kPeriod, out_);
  }
  EXPECT_NEAR(stage_.forceCommand()[1], -8.0 + 10.0 * (-8.0) * 20 * kPeriod, 1e-9);
  for (int cycle = 0; cycle < 2000; ++cycle) {
    stage_.apply(in_, data_, Vector6d::Zero(), &wrench, kPeriod, out_);
  }
  EXPECT_NEAR(stage_.forceCommand()[1], -8.0 - 3.0, 1e-9) << "the integral term stops at 3 N";
  // No estimate this cycle: no error, the integral holds what it has.
  stage_.apply(in_, data_, Vector6d::Zero(), nullptr, kPeriod, out_);
  EXPECT_NEAR(stage_.forceCommand()[1], -11.0, 1e-9);
  // Deselected, the axis forgets its integral.
  in_.force_axes[1] = 0.0;
  in_.force_axes[0] = 1.0;
  stage_.apply(in_, data_, Vector6d::Zero(), nullptr, kPeriod, out_);
  in_.force_axes[1] = 1.0;
  stage_.apply(in_, data_, Vector6d::Zero(), nullptr, kPeriod, out_);
  EXPECT_NEAR(stage_.forceCommand()[1], -8.0, 1e-9);
}

TEST_F(ForceAxesTest, ThePushFadesBetweenOnceAndTwiceTheSpeedBound) {
  stage_.configure(
      {.proportional_gain = 0.0, .integral_gain_per_s = 10.0, .max_speed_m_per_s = 0.1});
  in_.force_axes[2] = 1.0;
  in_.wrench_target[2] = 10.0;
  const Vector6d wrench = onTool(Vector6d::Zero());
  Vector6d task_twist = Vector6d::Zero();
  task_twist[2] = 0.15;  // 1.5 x the bound, in the direction of the push
  stage_.apply(in_, data_, twistFromTask(task_twist), &wrench, kPeriod, out_);
  EXPECT_NEAR(stage_.forceCommand()[2], 0.5 * 10.0, 1e-9) << "half way: half the push";
  task_twist[2] = 0.25;
  stage_.apply(in_, data_, twistFromTask(task_twist), &wrench, kPeriod, out_);
  EXPECT_NEAR(stage_.forceCommand()[2], 0.0, 1e-12);
  // Moving against the push (the surface pushing back) does not fade it; the integral resumes
  // from where it froze (nothing was added while fading).
  task_twist[2] = -0.3;
  stage_.apply(in_, data_, twistFromTask(task_twist), &wrench, kPeriod, out_);
  EXPECT_NEAR(stage_.forceCommand()[2], 10.0 + 10.0 * 10.0 * kPeriod, 1e-9);
}

TEST_F(ForceAxesTest, ATorqueAxisTakesTheRotationalSpringOut) {
  stage_.configure({.proportional_gain = 0.5, .integral_gain_per_s = 5.0});
  in_.force_axes[3] = 1.0;  // about task x
  in_.wrench_target[3] = 0.5;
  const Vector6d wrench = onTool(Vector6d::Zero());
  stage_.apply(in_, data_, Vector6d::Zero(), &wrench, kPeriod, out_);
  const Vector6d error_in = errorInTask(in_);
  const Vector6d error_out = errorInTask(out_);
  EXPECT_NEAR(error_out[3], 0.0, 1e-9);
  EXPECT_NEAR(error_out[4], error_in[4], 1e-9);
  EXPECT_NEAR(error_out[5], error_in[5], 1e-9);
  EXPECT_NEAR(error_out.head<3>().norm(), error_in.head<3>().norm(), 1e-12);
  EXPECT_NEAR(schema::fromXyzw(out_.orientation).norm(), 1.0, 1e-12);
  EXPECT_NEAR(inTask(out_.wrench_feedforward)[3] - inTask(in_.wrench_feedforward)[3],
              0.5 + 0.5 * 0.5 + 5.0 * 0.5 * kPeriod, 1e-9);
}

TEST_F(ForceAxesTest, TheContactLimitPullsTheReferenceBackAndReturnsIt) {
  stage_.configure({.max_speed_m_per_s = 0.1,
                    .contact_force_limit_n = Vector3d(0.0, 0.0, 10.0),  // task z only
                    .limit_bandwidth_hz = 2.0});
  const double error_z = errorInTask(in_)[2];
  ASSERT_GT(std::abs(error_z), 1e-3);
  const double sign = error_z > 0.0 ? 1.0 : -1.0;
  Vector6d exerted = Vector6d::Zero();
  exerted[2] = sign * 14.0;  // 4 N over the limit, in the direction the spring pushes
  const Vector6d over = onTool(exerted);
  stage_.apply(in_, data_, Vector6d::Zero(), &over, kPeriod, out_);
  const double rate = 2.0 * M_PI * 2.0 * 4.0 / kStiffness;  // m/s
  EXPECT_NEAR(stage_.pullBack()[2], rate * kPeriod, 1e-12);
  EXPECT_NEAR(errorInTask(out_)[2], error_z - sign * rate * kPeriod, 1e-12);
  EXPECT_NEAR(errorInTask(out_)[0], errorInTask(in_)[0], 1e-12) << "x has no limit";
  // The feedforward along z is clipped to the limit too.
  in_.wrench_feedforward[0] = 0.0;
  const Eigen::Matrix3d r = task_.toRotationMatrix();
  Map<Vector3d>(in_.wrench_feedforward) = r * Vector3d(0.0, 0.0, 25.0);
  stage_.apply(in_, data_, Vector6d::Zero(), &over, kPeriod, out_);
  EXPECT_NEAR(inTask(out_.wrench_feedforward)[2], 10.0, 1e-9);
  // Pulled back no further than onto the measured pose.
  for (int cycle = 0; cycle < 5000; ++cycle) {
    stage_.apply(in_, data_, Vector6d::Zero(), &over, kPeriod, out_);
  }
  EXPECT_NEAR(stage_.pullBack()[2], std::abs(error_z), 1e-12);
  // A cycle without a reading holds the pull-back (the spring's force stays off the contact).
  stage_.apply(in_, data_, Vector6d::Zero(), nullptr, kPeriod, out_);
  EXPECT_NEAR(stage_.pullBack()[2], std::abs(error_z), 1e-12);
  EXPECT_NEAR(errorInTask(out_)[2], 0.0, 1e-12);
  // Below the limit the reference comes back, at most at the speed bound.
  exerted[2] = 0.0;
  const Vector6d free = onTool(exerted);
  const double before = stage_.pullBack()[2];
  stage_.apply(in_, data_, Vector6d::Zero(), &free, kPeriod, out_);
  EXPECT_NEAR(before - stage_.pullBack()[2],
              std::min(2.0 * M_PI * 2.0 * 10.0 / kStiffness, 0.1) * kPeriod, 1e-12);
  // A force pulling the other way (not the spring's doing) never pulls the reference.
  exerted[2] = -sign * 50.0;
  const Vector6d away = onTool(exerted);
  for (int cycle = 0; cycle < 5000; ++cycle) {
    stage_.apply(in_, data_, Vector6d::Zero(), &away, kPeriod, out_);
  }
  EXPECT_EQ(stage_.pullBack()[2], 0.0);
}

TEST_F(ForceAxesTest, TheLimitClipsTheForceLoopToo) {
  stage_.configure({.contact_force_limit_n = Vector3d(0.0, 0.0, 12.0)});
  in_.force_axes[2] = 1.0;
  in_.wrench_target[2] = 30.0;
  const Vector6d wrench = onTool(Vector6d::Zero());
  stage_.apply(in_, data_, Vector6d::Zero(), &wrench, kPeriod, out_);
  EXPECT_EQ(stage_.forceCommand()[2], 12.0);
  // The command's own feedforward along the axis counts toward the limit too.
  in_.wrench_target[2] = 10.0;
  Map<Vector3d>(in_.wrench_feedforward) = task_.toRotationMatrix() * Vector3d(0.0, 0.0, 5.0);
  stage_.apply(in_, data_, Vector6d::Zero(), &wrench, kPeriod, out_);
  EXPECT_NEAR(inTask(out_.wrench_feedforward)[2], 12.0, 1e-9);
}

}  // namespace
}  // namespace comply::pipeline::test
