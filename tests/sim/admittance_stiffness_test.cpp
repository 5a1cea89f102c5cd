// The stiffness an arm renders, identified from a force-displacement sweep in simulation
// (experiments/output_modes: a known wrench at the TCP along each axis of a turned task frame,
// the steady displacement measured on the plant, K = F / d). The UR5e in admittance on position
// and on velocity servos renders the commanded stiffness within 10 % per axis, and so does the
// same law in torque mode on the torque-actuated UR5e.

#include <gtest/gtest.h>

#include <string>

#include "output_modes/output_modes_experiment.hpp"

namespace comply::testing {
namespace {

void expectRendered(OutputMode mode) {
  const experiments::IdentifiedStiffness found = experiments::identifyStiffness(mode);
  const char* axes[] = {"x", "y", "z", "rx", "ry", "rz"};
  for (std::size_t axis = 0; axis < 6; ++axis) {
    EXPECT_GT(found.commanded[axis], 0.0);
    EXPECT_NEAR(found.rendered[axis], found.commanded[axis], 0.1 * found.commanded[axis])
        << toString(mode) << " drives, task axis " << axes[axis];
  }
  ::testing::Test::RecordProperty("worst_error_percent", std::to_string(found.worstErrorPercent()));
}

TEST(RenderedStiffness, AdmittanceOnPositionServosRendersTheCommandedStiffness) {
  expectRendered(OutputMode::kPosition);
}

TEST(RenderedStiffness, AdmittanceOnVelocityServosRendersTheCommandedStiffness) {
  expectRendered(OutputMode::kVelocity);
}

TEST(RenderedStiffness, TorqueModeOnTheTorqueArmRendersTheSameStiffness) {
  expectRendered(OutputMode::kTorque);
}

}  // namespace
}  // namespace comply::testing
