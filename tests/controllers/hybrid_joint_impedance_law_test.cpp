// hybrid_joint_impedance on its own: the parameters it refuses (with the message a user sees when
// a controller does not start) and one step worked out by hand. Inputs are hand-written and every
// product and sum is exact in binary, so the expected torques are exact. The law against the
// published formula on the FR3's real Jacobian and Coriolis terms is tests/apps/droid_profile_test.

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <memory>
#include <string>
#include <vector>

#include "bus_values.hpp"
#include "comply/plugin/abi.h"
#include "comply/plugin/loader.hpp"

namespace comply::plugin {
namespace {

using law_test::writeJoints;

std::shared_ptr<const PluginLibrary> hybridLibrary() {
  return std::make_shared<const PluginLibrary>(COMPLY_TEST_HYBRID_JOINT_IMPEDANCE,
                                               COMPLY_COMMAND_JOINT);
}

ParameterMap numbersParameter(const std::string& name, const std::vector<double>& values) {
  ParameterMap parameters;
  parameters[name].numbers = values;
  return parameters;
}

void expectCreateRefused(const ParameterMap& parameters, const std::string& cause) {
  try {
    PluginInstance law(hybridLibrary(), 7, parameters);
    FAIL() << "create accepted parameters that should be refused: " << cause;
  } catch (const PluginError& error) {
    EXPECT_EQ(error.code(), PluginErrc::kCreateFailed);
    EXPECT_NE(std::string(error.what()).find(cause), std::string::npos) << error.what();
  }
}

/// Torques of one step; entries past dof must stay untouched (pre-filled with NaN).
std::vector<double> stepTorque(PluginInstance& law, const comply_input& input,
                               const comply_joint_command& command) {
  comply_output output{};
  for (double& torque : output.torque) {
    torque = std::numeric_limits<double>::quiet_NaN();
  }
  EXPECT_EQ(law.step(input, &command, output), COMPLY_OK) << output.message;
  for (int i = law.dof(); i < COMPLY_MAX_DOF; ++i) {
    EXPECT_TRUE(std::isnan(output.torque[i])) << "torque written past dof at index " << i;
  }
  return {output.torque, output.torque + law.dof()};
}

TEST(HybridJointImpedanceParameters, WrongLengthKxIsRefused) {
  expectCreateRefused(numbersParameter("Kx", {750.0, 750.0, 750.0, 15.0, 15.0}),
                      "parameter 'Kx' must be a list of exactly 6 numbers");
  expectCreateRefused(numbersParameter("Kx", std::vector<double>(7, 10.0)), "'Kx'");
}

TEST(HybridJointImpedanceParameters, TextKxdIsRefused) {
  ParameterMap parameters;
  parameters["Kxd"].text = "stiff";
  parameters["Kxd"].is_text = true;
  expectCreateRefused(parameters, "parameter 'Kxd' must be a list of exactly 6 numbers");
}

TEST(HybridJointImpedanceParameters, NegativeOrNonFiniteGainsAreRefused) {
  expectCreateRefused(numbersParameter("Kxd", {37.0, 37.0, -1.0, 2.0, 2.0, 2.0}),
                      "parameter 'Kxd' entry 2 is -1; gains must be finite and >= 0");
  expectCreateRefused(numbersParameter("Kx", {750.0, 750.0, 750.0, std::nan(""), 15.0, 15.0}),
                      "parameter 'Kx' entry 3");
  expectCreateRefused(numbersParameter("Kx", {750.0, std::numeric_limits<double>::infinity(), 750.0,
                                              15.0, 15.0, 15.0}),
                      "parameter 'Kx' entry 1");
}

TEST(HybridJointImpedanceParameters, AsksForJacobianAndCoriolis) {
  const PluginInstance law(hybridLibrary(), 7, {});
  EXPECT_EQ(law.requiredQuantities(), std::uint32_t{COMPLY_NEED_JACOBIAN | COMPLY_NEED_CORIOLIS});
}

TEST(HybridJointImpedanceLaw, TwoJointsByHand) {
  ParameterMap parameters = numbersParameter("Kx", {100.0, 100.0, 100.0, 10.0, 10.0, 10.0});
  parameters["Kxd"].numbers = {8.0, 8.0, 8.0, 2.0, 2.0, 2.0};
  PluginInstance law(hybridLibrary(), 2, parameters);

  comply_input input{};
  input.dof = 2;
  input.available = COMPLY_NEED_POSE | COMPLY_NEED_JACOBIAN | COMPLY_NEED_CORIOLIS;
  writeJoints({0.25, 0.5}, input.position);
  writeJoints({0.5, -1.0}, input.velocity);
  // Column-major 6 x 2: joint 0 moves the tip along x and turns it about z, joint 1 half as far.
  input.jacobian[0 * 6 + 0] = 1.0;
  input.jacobian[0 * 6 + 5] = 1.0;
  input.jacobian[1 * 6 + 0] = 0.5;
  input.jacobian[1 * 6 + 5] = 1.0;
  writeJoints({0.125, -0.25}, input.coriolis);

  comply_joint_command command{};
  command.dof = 2;
  writeJoints({0.75, 0.25}, command.position);
  // The velocity target is ignored: the damping acts on dq alone, as in polymetis.
  writeJoints({3.0, 3.0}, command.velocity);
  writeJoints({40.0, 30.0}, command.stiffness);
  writeJoints({4.0, 6.0}, command.damping);
  writeJoints({1.0, -0.5}, command.torque_feedforward);

  // e = (0.5, -0.25); J e = (x 0.375, rz 0.25); J dq = (x 0, rz -0.5).
  // Wrench: fx = 100 * 0.375 - 8 * 0 = 37.5, mz = 10 * 0.25 + 2 * 0.5 = 3.5.
  // J^T w = (37.5 + 3.5, 0.5 * 37.5 + 3.5) = (41, 22.25).
  // Joint: (40 * 0.5 - 4 * 0.5, 30 * -0.25 + 6 * 1) = (18, -1.5).
  // tau = J^T w + joint + coriolis + feedforward.
  const std::vector<double> torque = stepTorque(law, input, command);
  EXPECT_EQ(torque[0], 41.0 + 18.0 + 0.125 + 1.0);
  EXPECT_EQ(torque[1], 22.25 - 1.5 - 0.25 - 0.5);
}

TEST(HybridJointImpedanceLaw, DefaultsArePolymetisFrankaGains) {
  PluginInstance law(hybridLibrary(), 1, {});
  comply_input input{};
  input.dof = 1;
  input.velocity[0] = 0.5;
  for (int row = 0; row < 6; ++row) {
    input.jacobian[row] = 1.0;  // J^T K J = the sum of K's diagonal
  }
  comply_joint_command command{};
  command.dof = 1;
  command.position[0] = 0.5;
  // sum(Kx) = 2295, sum(Kxd) = 117: 2295 * 0.5 - 117 * 0.5.
  EXPECT_EQ(stepTorque(law, input, command)[0], 1089.0);
}

}  // namespace
}  // namespace comply::plugin
