// The stiffness an arm renders, identified from a force-displacement sweep in simulation: a known
// wrench at the TCP along each axis of a turned task frame, the steady displacement along that
// axis measured on the plant (MuJoCo's TCP pose, not the controller's model), K = F / d. The
// UR5e in admittance on position and velocity servos renders the commanded stiffness within 10 %
// per axis, and so does the same law in torque mode on the torque-actuated UR5e.
//
// The torque arm runs without robot.yaml's Coulomb friction: on a torque arm it leaves a dead
// band of +-f/K around the rest position (with it the UR5e stops 15 % short of K's displacement
// along task x), while the servos of a position-controlled arm remove it with their integral.

#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <cstdio>
#include <string>

#include "output_modes_support.hpp"

namespace comply::testing {
namespace {

const Eigen::Vector3d kTranslational(800.0, 1500.0, 2500.0);  // N/m, task x y z
const Eigen::Vector3d kRotational(40.0, 60.0, 90.0);          // N m/rad
constexpr double kForceN = 15.0;
constexpr double kTorqueNm = 1.5;
constexpr int kSettleCycles = 1500;
constexpr int kPushCycles = 2500;

struct Identified {
  Eigen::Vector3d translational, rotational;
};

/// Where the TCP is, in the task frame: position [m] and a rotation vector [rad] from `reference`.
Vector6d displacement(const Eigen::Isometry3d& reference, const Eigen::Isometry3d& now) {
  const Eigen::Matrix3d task = turnedTaskFrame().toRotationMatrix();
  Vector6d moved;
  moved.head<3>() = task.transpose() * (now.translation() - reference.translation());
  const Eigen::AngleAxisd turned(now.linear() * reference.linear().transpose());
  moved.tail<3>() = task.transpose() * (turned.angle() * turned.axis());
  return moved;
}

Identified identify(OutputMode mode, OutputMode actuation) {
  sim::PlantOptions plant = plantOf(actuation);
  plant.friction_scale = actuation == OutputMode::kTorque ? 0.0 : 1.0;
  OutputModeRig<> rig(outputModeConfig("ur5e", mode, kTranslational, kRotational), plant);
  for (int cycle = 0; cycle < kSettleCycles; ++cycle) {
    EXPECT_TRUE(rig.cycle()) << "settling, cycle " << cycle << ": "
                             << rig.wrapper.diagnostics().last_fault;
  }
  const Eigen::Matrix3d task = turnedTaskFrame().toRotationMatrix();
  Identified found;
  for (int axis = 0; axis < 6; ++axis) {
    const Eigen::Isometry3d before = rig.plant.tcpPose();
    Vector6d push = Vector6d::Zero();
    const bool force = axis < 3;
    const Eigen::Vector3d along = task.col(axis % 3) * (force ? kForceN : kTorqueNm);
    (force ? push.head<3>() : push.tail<3>()) = along;
    rig.plant.setExternalWrench(push);
    for (int cycle = 0; cycle < kPushCycles; ++cycle) {
      EXPECT_TRUE(rig.cycle()) << "axis " << axis << ", cycle " << cycle << ": "
                               << rig.wrapper.diagnostics().last_fault;
    }
    const double moved = displacement(before, rig.plant.tcpPose())[axis];
    (force ? found.translational : found.rotational)[axis % 3] =
        (force ? kForceN : kTorqueNm) / moved;
    rig.plant.setExternalWrench(Vector6d::Zero());
    for (int cycle = 0; cycle < kPushCycles; ++cycle) {
      EXPECT_TRUE(rig.cycle());
    }
  }
  return found;
}

void expectRendered(const Identified& found, const std::string& label) {
  for (int axis = 0; axis < 3; ++axis) {
    EXPECT_NEAR(found.translational[axis], kTranslational[axis], 0.1 * kTranslational[axis])
        << label << ", task axis " << "xyz"[axis];
    EXPECT_NEAR(found.rotational[axis], kRotational[axis], 0.1 * kRotational[axis])
        << label << ", task axis r" << "xyz"[axis];
    std::printf("%s: K_%c %.1f N/m (commanded %.0f), K_r%c %.2f N m/rad (commanded %.0f)\n",
                label.c_str(), "xyz"[axis], found.translational[axis], kTranslational[axis],
                "xyz"[axis], found.rotational[axis], kRotational[axis]);
  }
}

TEST(RenderedStiffness, AdmittanceOnPositionServosRendersTheCommandedStiffness) {
  expectRendered(identify(OutputMode::kPosition, OutputMode::kPosition), "position");
}

TEST(RenderedStiffness, AdmittanceOnVelocityServosRendersTheCommandedStiffness) {
  expectRendered(identify(OutputMode::kVelocity, OutputMode::kVelocity), "velocity");
}

TEST(RenderedStiffness, TorqueModeOnTheTorqueArmRendersTheSameStiffness) {
  expectRendered(identify(OutputMode::kTorque, OutputMode::kTorque), "torque");
}

}  // namespace
}  // namespace comply::testing
