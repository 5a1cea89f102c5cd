// Joint impedance tau = K (q_d - q) + D (dq_d - dq) + tau_ff against torques worked out by hand.
// Values are chosen so that every product and sum is exact in binary, so the expected torques are
// exact too and the tolerance only has to absorb the order of operations.

#include <gtest/gtest.h>

#include <vector>

#include "law_test_support.hpp"
#include "test_urdfs.hpp"

namespace comply::law_test {
namespace {

constexpr double kExactTolerance = 1e-12;

model::Model pendulumModel() {
  model::ModelOptions options;
  options.joint_names = {"hinge"};
  options.tip_frame = "tip";
  return model::Model::fromUrdfString(test_urdfs::pendulum(), options);
}

model::Model planarTwoLinkModel() {
  model::ModelOptions options;
  options.joint_names = {"shoulder", "elbow"};
  options.tip_frame = "tip";
  return model::Model::fromUrdfString(test_urdfs::planarTwoLink(), options);
}

comply_joint_command jointCommand(int dof) {
  comply_joint_command command{};
  command.dof = dof;
  command.fields = COMPLY_FIELD_POSITION | COMPLY_FIELD_VELOCITY | COMPLY_FIELD_STIFFNESS |
                   COMPLY_FIELD_DAMPING | COMPLY_FIELD_TORQUE_FEEDFORWARD;
  return command;
}

TEST(JointImpedanceLaw, PendulumSpringDamperAndFeedforward) {
  const model::Model model = pendulumModel();
  ASSERT_EQ(model.dof(), 1);
  plugin::PluginInstance law(jointImpedanceLibrary(), model.dof(), {});
  const comply_input input = inputFromModel(model, {0.25}, {-0.5});

  comply_joint_command command = jointCommand(model.dof());
  command.position[0] = 0.75;
  command.velocity[0] = 0.5;
  command.stiffness[0] = 40.0;
  command.damping[0] = 3.0;
  command.torque_feedforward[0] = 1.5;

  // 40 (0.75 - 0.25) + 3 (0.5 + 0.5) + 1.5 = 20 + 3 + 1.5
  const Eigen::VectorXd torque = stepTorque(law, input, &command);
  EXPECT_NEAR(torque[0], 24.5, kExactTolerance);
}

TEST(JointImpedanceLaw, PendulumSpringPullsTowardTarget) {
  const model::Model model = pendulumModel();
  plugin::PluginInstance law(jointImpedanceLibrary(), model.dof(), {});
  const comply_input input = inputFromModel(model, {0.5}, {0.0});

  comply_joint_command command = jointCommand(model.dof());
  command.position[0] = 0.25;  // target below the measured angle: the spring pushes negative
  command.stiffness[0] = 16.0;

  const Eigen::VectorXd torque = stepTorque(law, input, &command);
  EXPECT_NEAR(torque[0], -4.0, kExactTolerance);
}

TEST(JointImpedanceLaw, PlanarTwoLinkPerJointGains) {
  const model::Model model = planarTwoLinkModel();
  ASSERT_EQ(model.dof(), 2);
  plugin::PluginInstance law(jointImpedanceLibrary(), model.dof(), {});
  const comply_input input = inputFromModel(model, {0.25, 0.5}, {0.5, 0.25});

  comply_joint_command command = jointCommand(model.dof());
  writeJoints({0.5, -0.25}, command.position);
  writeJoints({0.0, 1.0}, command.velocity);
  writeJoints({120.0, 60.0}, command.stiffness);
  writeJoints({8.0, 4.0}, command.damping);
  writeJoints({-2.0, 0.75}, command.torque_feedforward);

  const Eigen::VectorXd torque = stepTorque(law, input, &command);
  // Shoulder: 120 (0.5 - 0.25) + 8 (0 - 0.5) - 2 = 30 - 4 - 2.
  EXPECT_NEAR(torque[0], 24.0, kExactTolerance);
  // Elbow: 60 (-0.25 - 0.5) + 4 (1 - 0.25) + 0.75 = -45 + 3 + 0.75; gains must not mix joints.
  EXPECT_NEAR(torque[1], -41.25, kExactTolerance);
}

TEST(JointImpedanceLaw, ZeroGainsLeaveOnlyFeedforward) {
  const model::Model model = planarTwoLinkModel();
  plugin::PluginInstance law(jointImpedanceLibrary(), model.dof(), {});
  const comply_input input = inputFromModel(model, {1.0, -1.0}, {2.0, -3.0});

  comply_joint_command command = jointCommand(model.dof());
  command.position[0] = -1.0;
  command.velocity[1] = 4.0;
  writeJoints({0.125, -7.0}, command.torque_feedforward);

  const Eigen::VectorXd torque = stepTorque(law, input, &command);
  EXPECT_EQ(torque[0], 0.125);
  EXPECT_EQ(torque[1], -7.0);
}

}  // namespace
}  // namespace comply::law_test
