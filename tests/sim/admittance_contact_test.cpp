// Admittance in contact and under a heavy tool, on the position-servoed UR5e with the default
// virtual inertia (the arm's own):
//   - pressing a rigid table: the probe comes down, the reference goes 3 cm past the surface; the
//     contact is never lost after the first touch (no bounce), the force settles at K x 3 cm
//     within 10 %, and its peak and settling time are those of the torque-driven arm pressing
//     the same way (within 25 % and 50 %);
//   - a 3 kg tool (its inertial force in the wrist sensor's reading, as on a real arm): a 5 cm
//     step of the reference ends at rest without ringing.

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "output_modes_support.hpp"

namespace comply::testing {
namespace {

constexpr double kPressStiffness = 1000.0;  // N/m along the pressing axis (base z)
constexpr double kPenetrationM = 0.03;      // reference past the surface
constexpr double kContactZ = 0.41;          // TCP height at first touch (table 0.30 + probe 0.11)

struct Press {
  double peak_n = 0.0, final_n = 0.0, settling_s = 0.0;
  int contact_losses = 0;  ///< cycles without contact after the first touch
};

/// Smooth straight-line reference from `from` to `to` over [start, end] cycles.
CartesianCommand along(int cycle, int start, int end, const Eigen::Vector3d& from,
                       const Eigen::Vector3d& to, const Eigen::Quaterniond& orientation, int dof) {
  const double s = std::clamp(static_cast<double>(cycle - start) / (end - start), 0.0, 1.0);
  CartesianCommand target = CartesianCommand::zero(dof);
  target.fields = CommandField::kPosition;
  target.stamp_s = cycle * kOutputPeriodS;
  target.position = from + (3.0 * s * s - 2.0 * s * s * s) * (to - from);
  target.orientation = orientation;
  return target;
}

Press press(OutputMode mode) {
  pipeline::WrapperConfig config = simCartesianConfig("ur5e");
  config.output.mode = mode;
  config.initial_cartesian.stiffness_translational =
      Eigen::Vector3d(2000.0, 2000.0, kPressStiffness).asDiagonal();
  sim::PlantOptions options = plantOf(mode);
  options.substeps = 2;
  options.scene.tool = kSourceDir / "examples" / "sim" / "probe_tool.xml";
  options.scene.objects = {kSourceDir / "examples" / "sim" / "table.xml"};
  OutputModeRig<> rig(config, options);
  const int dof = rig.wrapper.dof();
  const MeasuredPose home = rig.wrapper.measuredPose();
  const Eigen::Vector3d start = home.tcp_position;
  // The home orientation turned the least so that TCP z (the probe) points down.
  const Eigen::Quaterniond down =
      Eigen::Quaterniond::FromTwoVectors(home.tcp_orientation * Eigen::Vector3d::UnitZ(),
                                         -Eigen::Vector3d::UnitZ()) *
      home.tcp_orientation;
  const Eigen::Vector3d above(0.45, 0.1, kContactZ + 0.02);
  const Eigen::Vector3d pressed(0.45, 0.1, kContactZ - kPenetrationM);
  Press result;
  std::vector<double> force;
  bool touched = false;
  for (int cycle = 0; cycle < 7000; ++cycle) {
    const CartesianCommand target =
        cycle < 3000 ? along(cycle, 0, 2500, start, above, down, dof)
                     : along(cycle, 3000, 4000, above, pressed, down, dof);
    const pipeline::Verdict verdict = rig.wrapper.submit(target);
    EXPECT_TRUE(verdict.accepted) << "cycle " << cycle << ": " << verdict.message;
    if (!verdict.accepted) {
      return result;
    }
    EXPECT_TRUE(rig.cycle()) << "cycle " << cycle << ": " << rig.wrapper.diagnostics().last_fault;
    const double normal = rig.plant.toolContactWrench()[2];  // the table pushes up
    touched = touched || normal > 0.0;
    if (touched) {
      force.push_back(normal);
      result.contact_losses += normal <= 0.0 ? 1 : 0;
      result.peak_n = std::max(result.peak_n, normal);
    }
  }
  for (std::size_t i = force.size() - 500; i < force.size(); ++i) {
    result.final_n += force[i] / 500.0;
  }
  for (std::size_t i = force.size(); i-- > 0;) {
    if (std::abs(force[i] - result.final_n) > 0.05 * result.final_n) {
      result.settling_s = static_cast<double>(i + 1) * kOutputPeriodS;
      break;
    }
  }
  std::printf("%s: peak %.1f N, final %.1f N (K x d = %.1f N), settled within 5 %% %.3f s after "
              "the first touch, %d cycles without contact after it\n",
              std::string(toString(mode)).c_str(), result.peak_n, result.final_n,
              kPressStiffness * kPenetrationM, result.settling_s, result.contact_losses);
  return result;
}

TEST(AdmittanceContact, PressingARigidTableDoesNotBounce) {
  const Press admittance = press(OutputMode::kPosition);
  EXPECT_EQ(admittance.contact_losses, 0) << "the probe left the table after touching it";
  EXPECT_NEAR(admittance.final_n, kPressStiffness * kPenetrationM,
              0.1 * kPressStiffness * kPenetrationM);
  // The impact of the same approach on the torque-driven arm, the reference beside it.
  const Press torque = press(OutputMode::kTorque);
  EXPECT_NEAR(torque.final_n, kPressStiffness * kPenetrationM,
              0.1 * kPressStiffness * kPenetrationM);
  EXPECT_LT(admittance.peak_n, 1.25 * torque.peak_n);
  EXPECT_LT(admittance.settling_s, 1.5 * torque.settling_s + 0.05);
}

TEST(AdmittanceContact, AHeavyToolDoesNotRing) {
  pipeline::WrapperConfig config = simCartesianConfig("ur5e");
  config.output.mode = OutputMode::kPosition;
  config.payload_compensation = true;  // the tool, declared (without: it rings, see docs)
  config.payload.mass_kg = 3.01;
  config.payload.com_in_tip = Eigen::Vector3d(0.0, 0.0, (3.0 * 0.05 + 0.01 * 0.1) / 3.01);
  sim::PlantOptions options = plantOf(OutputMode::kPosition);
  options.scene.tool = kSourceDir / "examples" / "sim" / "payload_3kg.xml";
  OutputModeRig<> rig(config, options);
  const int dof = rig.wrapper.dof();
  const MeasuredPose home = rig.wrapper.measuredPose();
  CartesianCommand step = CartesianCommand::zero(dof);
  step.fields = CommandField::kPosition;
  step.position = home.tcp_position + Eigen::Vector3d(0.0, 0.05, 0.0);
  step.orientation = home.tcp_orientation;
  double settled_speed = 0.0;
  double overshoot_m = 0.0;
  int crossings = 0;
  double last_error = -1.0;
  Eigen::Vector3d last_position = rig.plant.tcpPose().translation();
  for (int cycle = 0; cycle < 4000; ++cycle) {
    if (cycle == 500) {
      step.stamp_s = cycle * kOutputPeriodS;
      ASSERT_TRUE(rig.wrapper.submit(step).accepted);
    }
    ASSERT_TRUE(rig.cycle()) << "cycle " << cycle << ": " << rig.wrapper.diagnostics().last_fault;
    const Eigen::Vector3d position = rig.plant.tcpPose().translation();
    if (cycle > 500) {
      const double error = position.y() - step.position.y();  // negative until it arrives
      overshoot_m = std::max(overshoot_m, error);
      crossings += (error > 0.0) != (last_error > 0.0) ? 1 : 0;
      last_error = error;
    }
    if (cycle >= 3500) {
      settled_speed = std::max(settled_speed, (position - last_position).norm() / kOutputPeriodS);
    }
    last_position = position;
  }
  std::printf("3 kg tool, 5 cm step: overshoot %.2f mm, %d crossings of the target, largest "
              "speed in the last 0.5 s %.2f mm/s\n",
              overshoot_m * 1e3, crossings, settled_speed * 1e3);
  EXPECT_LT(overshoot_m, 0.005) << "10 % of the step";
  EXPECT_LE(crossings, 2) << "ringing about the target";
  EXPECT_LT(settled_speed, 1e-3);
}

}  // namespace
}  // namespace comply::testing
