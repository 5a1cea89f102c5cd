// Ratio-mode damping through the plugin along a moving trajectory, every cycle: the warm-started
// fast path (fixed-size law for 6 and 7 joints, dynamic for 12) against a generalised eigen solve
// of K v = w Lambda v (Eigen) on the same inputs, while the stiffness, its task frame and the
// ratios change mid-run. D must be right on the very cycle a new K or zeta arrives.

#include <gtest/gtest.h>

#include <Eigen/Eigenvalues>
#include <Eigen/LU>
#include <filesystem>

#include "comply/host/synthetic_chain.hpp"
#include "law_test_support.hpp"

namespace comply::law_test {
namespace {

constexpr double kPromisedRelativeError = 1e-6;
constexpr double kInertiaRegularisation = 1e-6;  // the plugin's default

Matrix6d expectedDamping(const comply_input& input, const Matrix6d& stiffness,
                         const Eigen::Matrix3d& task, const Vector6d& ratio) {
  const Matrix6Xd jacobian = jacobianOf(input);
  const Matrix6d inverse_inertia = jacobian * massMatrixOf(input).inverse() * jacobian.transpose() +
                                   kInertiaRegularisation * Matrix6d::Identity();
  const Matrix6d inertia = inverse_inertia.inverse();
  const Eigen::GeneralizedSelfAdjointEigenSolver<Matrix6d> eigen(stiffness, inertia);
  const Matrix6d modes = inertia * eigen.eigenvectors();
  const Matrix6d critical = modes *
                            (2.0 * eigen.eigenvalues().cwiseMax(0.0).cwiseSqrt()).asDiagonal() *
                            modes.transpose();
  Matrix6d root = Matrix6d::Zero();
  root.topLeftCorner<3, 3>() = task * ratio.head<3>().cwiseSqrt().asDiagonal() * task.transpose();
  root.bottomRightCorner<3, 3>() =
      task * ratio.tail<3>().cwiseSqrt().asDiagonal() * task.transpose();
  return root * critical * root;
}

struct Gains {
  Eigen::Vector3d translational;
  Eigen::Vector3d rotational;
  Eigen::Matrix3d task;
  Vector6d ratio;
};

/// Returns the largest relative torque error over the run.
double worstErrorAlongTrajectory(const model::RobotDescription& robot) {
  const model::Model model = robot.loadModel();
  const int dof = model.dof();
  plugin::PluginInstance law(cartesianImpedanceLibrary(), dof, {});
  Gains gains{{800.0, 500.0, 150.0},
              {40.0, 25.0, 8.0},
              Eigen::AngleAxisd(0.4, Eigen::Vector3d(0.2, -1.0, 0.6).normalized()).matrix(),
              Vector6d::Ones()};
  double worst = 0.0;
  for (int cycle = 0; cycle < 300; ++cycle) {
    if (cycle == 100) {  // a new stiffness in a new task frame
      gains.translational = {300.0, 1200.0, 600.0};
      gains.task = Eigen::AngleAxisd(-1.1, Eigen::Vector3d(1.0, 0.3, 0.2).normalized()).matrix();
    }
    if (cycle == 150) {  // per-axis ratios
      gains.ratio << 0.5, 1.0, 2.0, 0.7, 1.0, 1.5;
    }
    if (cycle == 200) {  // nearly isotropic: near-repeated eigenvalues
      gains.translational = {500.0, 500.0, 500.0 * (1.0 + 1e-9)};
      gains.rotational = {30.0, 30.0, 30.0};
    }
    std::vector<double> q = robot.home;
    std::vector<double> dq(q.size());
    for (int i = 0; i < dof; ++i) {
      const double omega = 2.0 * M_PI * (0.5 + 0.1 * i);
      q[i] += 0.1 * std::sin(omega * cycle * 0.001 + i);
      dq[i] = 0.1 * omega * std::cos(omega * cycle * 0.001 + i);
    }
    const comply_input input = inputFromModel(model, q, dq);
    comply_cartesian_command command = holdCommand(input);
    writeRowMajor(gains.translational.asDiagonal().toDenseMatrix(),
                  command.stiffness_translational);
    writeRowMajor(gains.rotational.asDiagonal().toDenseMatrix(), command.stiffness_rotational);
    writeXyzw(Eigen::Quaterniond(gains.task), command.task_frame);
    command.damping_mode = COMPLY_DAMPING_RATIO;
    for (int k = 0; k < 6; ++k) {
      command.damping_ratio[k] = gains.ratio[k];
    }
    Matrix6d stiffness = Matrix6d::Zero();
    stiffness.topLeftCorner<3, 3>() =
        gains.task * gains.translational.asDiagonal() * gains.task.transpose();
    stiffness.bottomRightCorner<3, 3>() =
        gains.task * gains.rotational.asDiagonal() * gains.task.transpose();
    const Matrix6Xd jacobian = jacobianOf(input);
    const Eigen::VectorXd velocity = Eigen::Map<const Eigen::VectorXd>(input.velocity, dof);
    const Eigen::VectorXd expected =
        -jacobian.transpose() *
        (expectedDamping(input, stiffness, gains.task, gains.ratio) * (jacobian * velocity));
    worst = std::max(worst, relativeError(stepTorque(law, input, &command), expected));
  }
  return worst;
}

TEST(CartesianRatioTracking, Fr3FixedSevenJointLaw) {
  EXPECT_LT(worstErrorAlongTrajectory(model::loadRobotDescription("fr3")), kPromisedRelativeError);
}

TEST(CartesianRatioTracking, Ur5eFixedSixJointLaw) {
  EXPECT_LT(worstErrorAlongTrajectory(model::loadRobotDescription("ur5e")), kPromisedRelativeError);
}

TEST(CartesianRatioTracking, TwelveJointChainDynamicLaw) {
  const std::filesystem::path folder = host::writeSyntheticChain(
      12, std::filesystem::temp_directory_path() / "comply-ratio-tracking-chain");
  const double worst = worstErrorAlongTrajectory(model::loadRobotDescription(folder.string()));
  std::filesystem::remove_all(folder);
  EXPECT_LT(worst, kPromisedRelativeError);
}

}  // namespace
}  // namespace comply::law_test
