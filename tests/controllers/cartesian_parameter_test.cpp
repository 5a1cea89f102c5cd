// Refusals of the Cartesian law: bad parameters at creation (a PluginError naming the cause, which
// is all a user sees when a controller does not start) and commands it cannot serve at step time.

#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "law_test_support.hpp"

namespace comply::law_test {
namespace {

void expectCreateRefused(const plugin::ParameterMap& parameters, const std::string& cause) {
  try {
    plugin::PluginInstance law(cartesianImpedanceLibrary(), 7, parameters);
    FAIL() << "create accepted parameters that should be refused: " << cause;
  } catch (const plugin::PluginError& error) {
    EXPECT_EQ(error.code(), plugin::PluginErrc::kCreateFailed);
    const std::string message = error.what();
    EXPECT_NE(message.find(cause), std::string::npos) << message;
    EXPECT_NE(message.find(COMPLY_TEST_CARTESIAN_IMPEDANCE), std::string::npos) << message;
  }
}

TEST(CartesianParameters, NegativeNullspaceDampingIsRefused) {
  expectCreateRefused(numberParameter("nullspace_dls_damping", -0.01), "nullspace_dls_damping");
  expectCreateRefused(numberParameter("nullspace_dls_damping", -0.01), ">= 0");
}

TEST(CartesianParameters, NanNullspaceDampingIsRefused) {
  expectCreateRefused(numberParameter("nullspace_dls_damping", std::nan("")),
                      "nullspace_dls_damping");
}

TEST(CartesianParameters, NegativeInertiaRegularisationIsRefused) {
  expectCreateRefused(numberParameter("inertia_regularisation", -1e-6), "inertia_regularisation");
}

TEST(CartesianParameters, ZeroNullspaceDampingIsAccepted) {
  EXPECT_NO_THROW(plugin::PluginInstance(cartesianImpedanceLibrary(), 7,
                                         numberParameter("nullspace_dls_damping", 0.0)));
}

TEST(CartesianParameters, MassMatrixRequestedOnlyForInertiaAwareDamping) {
  const plugin::PluginInstance aware(cartesianImpedanceLibrary(), 7, {});
  EXPECT_EQ(aware.requiredQuantities(),
            std::uint32_t{COMPLY_NEED_POSE | COMPLY_NEED_JACOBIAN | COMPLY_NEED_MASS_MATRIX});
  const plugin::PluginInstance unaware(cartesianImpedanceLibrary(), 7,
                                       numberParameter("inertia_aware_damping", 0.0));
  EXPECT_EQ(unaware.requiredQuantities(), std::uint32_t{COMPLY_NEED_POSE | COMPLY_NEED_JACOBIAN});
}

class CartesianStepRefusal : public ::testing::Test {
 protected:
  Fr3 fr3_;
  comply_input input_ = fr3_.inputAtHome();

  [[nodiscard]] comply_cartesian_command ratioCommand() const {
    comply_cartesian_command command = holdCommand(input_);
    writeRowMajor(500.0 * Eigen::Matrix3d::Identity(), command.stiffness_translational);
    writeRowMajor(30.0 * Eigen::Matrix3d::Identity(), command.stiffness_rotational);
    command.damping_mode = COMPLY_DAMPING_RATIO;
    for (double& ratio : command.damping_ratio) {
      ratio = 1.0;
    }
    return command;
  }

  /// The ratio command refused by `law` on `input`, with `reason` in the message.
  void expectRefused(plugin::PluginInstance& law, const comply_input& input,
                     const std::string& reason) {
    const comply_cartesian_command command = ratioCommand();
    comply_output output{};
    EXPECT_EQ(law.step(input, &command, output), COMPLY_ERROR);
    EXPECT_NE(std::string(output.message).find(reason), std::string::npos) << output.message;
  }
};

TEST_F(CartesianStepRefusal, RatioModeWithoutInertiaAwareDamping) {
  plugin::PluginInstance law(cartesianImpedanceLibrary(), 7,
                             numberParameter("inertia_aware_damping", 0.0));
  expectRefused(law, input_, "inertia_aware_damping");
}

TEST_F(CartesianStepRefusal, RatioModeWithSingularMassMatrix) {
  plugin::PluginInstance law(cartesianImpedanceLibrary(), 7, {});
  comply_input input = input_;
  for (double& entry : input.mass_matrix) {
    entry = 0.0;
  }
  expectRefused(law, input, "not positive definite");
}

TEST_F(CartesianStepRefusal, SameCommandSucceedsWithInertiaAwareDamping) {
  // The refusals above are about the mode and the inertia, not about the command itself.
  plugin::PluginInstance law(cartesianImpedanceLibrary(), 7, {});
  const comply_cartesian_command command = ratioCommand();
  comply_output output{};
  EXPECT_EQ(law.step(input_, &command, output), COMPLY_OK) << output.message;
}

}  // namespace
}  // namespace comply::law_test
