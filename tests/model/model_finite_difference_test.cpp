// Internal consistency of the model on every shipped robot, independent of any other library:
// the Jacobian is the derivative of the pose, gravity the gradient of the potential energy, the
// Coriolis vector what Lagrange's equations give from M(q), and M symmetric positive definite.

#include <gtest/gtest.h>

#include <Eigen/Cholesky>

#include "comply/model/robot_description.hpp"
#include "comply/model/update.hpp"
#include "robot_sampling.hpp"

namespace comply::model {
namespace {

constexpr int kSamples = 100;
constexpr double kStep = 1e-6;  // central differences: truncation ~1e-12, round-off ~1e-10

struct Evaluation {
  Eigen::Vector3d position;
  Eigen::Matrix3d rotation;
  JointMatrix mass_matrix;
  double potential_energy;
};

class FiniteDifferenceTest : public testing::ShippedRobotTest {
 protected:
  Evaluation evaluate(const std::vector<double>& q) {
    EXPECT_EQ(update(*model_, *data_, q, {}, Quantity::kPose | Quantity::kMassMatrix),
              UpdateStatus::kOk);
    double potential = 0.0;
    for (int i = 0; i < model_->dof(); ++i) {
      potential -= model_->body(i).mass_kg * model_->gravity().dot(data_->bodies[i].com);
    }
    return {data_->tip_position, data_->tip_rotation, data_->mass_matrix, potential};
  }
};

TEST_P(FiniteDifferenceTest, DerivativesAgree) {
  testing::JointSampler sampler(*model_, 7);
  const int dof = model_->dof();
  double worst_jacobian = 0.0;
  double worst_gravity = 0.0;
  double worst_coriolis = 0.0;
  for (int sample_index = 0; sample_index < kSamples; ++sample_index) {
    const testing::JointSample sample = sampler.next();
    ASSERT_EQ(update(*model_, *data_, sample.q, sample.dq, Quantity::kAll), UpdateStatus::kOk);
    const Jacobian jacobian = data_->jacobian;
    const JointVector gravity = data_->gravity;
    const JointVector coriolis = data_->coriolis;
    const JointMatrix mass = data_->mass_matrix;

    // M symmetric (exactly, by construction) and positive definite.
    EXPECT_EQ((mass - mass.transpose()).norm(), 0.0);
    Eigen::LLT<JointMatrix> cholesky(mass);
    EXPECT_EQ(cholesky.info(), Eigen::Success) << GetParam() << ": M not positive definite";

    // Lagrange: C dq = dM/dt dq - 1/2 d/dq (dq^T M dq), both by central differences.
    const Eigen::Map<const Eigen::VectorXd> dq(sample.dq.data(), dof);
    std::vector<double> forward = sample.q;
    std::vector<double> backward = sample.q;
    for (int i = 0; i < dof; ++i) {
      forward[i] = sample.q[i] + kStep * sample.dq[i];
      backward[i] = sample.q[i] - kStep * sample.dq[i];
    }
    const JointMatrix mass_rate =
        (evaluate(forward).mass_matrix - evaluate(backward).mass_matrix) / (2.0 * kStep);
    Eigen::VectorXd expected_coriolis = mass_rate * dq;

    for (int i = 0; i < dof; ++i) {
      forward = sample.q;
      backward = sample.q;
      forward[i] += kStep;
      backward[i] -= kStep;
      const Evaluation plus = evaluate(forward);
      const Evaluation minus = evaluate(backward);
      Eigen::Matrix<double, 6, 1> column;
      column.head<3>() = (plus.position - minus.position) / (2.0 * kStep);
      // dR/dq R^T = [w]x: take the axis of the small rotation between the two samples.
      const Eigen::AngleAxisd delta(plus.rotation * minus.rotation.transpose());
      column.tail<3>() = delta.axis() * delta.angle() / (2.0 * kStep);
      worst_jacobian = std::max(worst_jacobian, (column - jacobian.col(i)).cwiseAbs().maxCoeff());
      worst_gravity = std::max(
          worst_gravity,
          std::abs((plus.potential_energy - minus.potential_energy) / (2.0 * kStep) - gravity[i]));
      const double kinetic_gradient =
          0.5 * dq.dot((plus.mass_matrix - minus.mass_matrix) * dq) / (2.0 * kStep);
      expected_coriolis[i] -= kinetic_gradient;
    }
    worst_coriolis = std::max(worst_coriolis, (expected_coriolis - coriolis).cwiseAbs().maxCoeff());
  }
  EXPECT_LT(worst_jacobian, 1e-7) << GetParam();
  EXPECT_LT(worst_gravity, 1e-6) << GetParam();
  EXPECT_LT(worst_coriolis, 1e-6) << GetParam();
  std::cout << GetParam() << ": max |J - dpose/dq| " << worst_jacobian << ", |g - dV/dq| "
            << worst_gravity << ", |C dq - Lagrange| " << worst_coriolis << "\n";
}

INSTANTIATE_TEST_SUITE_P(Robots, FiniteDifferenceTest,
                         ::testing::ValuesIn(testing::shippedRobots()),
                         [](const auto& param_info) { return param_info.param; });

}  // namespace
}  // namespace comply::model
