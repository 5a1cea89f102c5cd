// The model against two independent implementations on every shipped robot: KDL (urdfdom ->
// KDL::Tree conversion in tests/support) and MuJoCo (its own URDF importer, fixed frames kept).

#include <gtest/gtest.h>

#include <algorithm>
#include <iostream>

#include "comply/model/robot_description.hpp"
#include "comply/model/update.hpp"
#include "kdl_reference.hpp"
#include "mujoco_reference.hpp"
#include "robot_sampling.hpp"

namespace comply::model {
namespace {

constexpr int kSamples = 1000;

/// Largest absolute difference per quantity over all samples.
struct WorstError {
  double position = 0.0;
  double rotation = 0.0;
  double jacobian = 0.0;
  double gravity = 0.0;
  double coriolis = 0.0;
  double mass_matrix = 0.0;

  void add(const Data& data, const testing::ReferenceResult& reference, int dof) {
    const auto max_abs = [](const auto& difference) { return difference.cwiseAbs().maxCoeff(); };
    position = std::max(position, max_abs(data.tip_position - reference.position));
    rotation =
        std::max(rotation, max_abs(data.tip_rotation - reference.orientation.toRotationMatrix()));
    jacobian = std::max(jacobian, max_abs(data.jacobian - reference.jacobian));
    gravity = std::max(gravity, max_abs(data.gravity - reference.gravity));
    coriolis = std::max(coriolis, max_abs(data.coriolis - reference.coriolis));
    mass_matrix = std::max(mass_matrix, max_abs(data.mass_matrix - reference.mass_matrix));
    EXPECT_EQ(reference.gravity.size(), dof);
  }

  void print(const std::string& label) const {
    std::cout << label << " max abs error over " << kSamples << " samples: position " << position
              << " m, rotation " << rotation << ", Jacobian " << jacobian << ", gravity " << gravity
              << " N m, Coriolis " << coriolis << " N m, mass matrix " << mass_matrix
              << " kg m^2\n";
  }
};

class ReferenceTest : public ::testing::TestWithParam<std::string> {
 protected:
  void SetUp() override {
    robot_ = loadRobotDescription(GetParam());
    model_ = std::make_unique<Model>(robot_.loadModel());
    data_ = std::make_unique<Data>(*model_);
  }

  /// The worst errors against `reference` (its compute(q, dq)) over kSamples joint samples of
  /// seed `seed`.
  template <typename Reference>
  WorstError worstAgainst(Reference& reference, unsigned seed, const std::string& label) {
    testing::JointSampler sampler(*model_, seed);
    WorstError worst;
    for (int i = 0; i < kSamples; ++i) {
      const testing::JointSample sample = sampler.next();
      EXPECT_EQ(update(*model_, *data_, sample.q, sample.dq, Quantity::kAll), UpdateStatus::kOk);
      const Eigen::VectorXd q = Eigen::Map<const Eigen::VectorXd>(sample.q.data(), sample.q.size());
      const Eigen::VectorXd dq =
          Eigen::Map<const Eigen::VectorXd>(sample.dq.data(), sample.dq.size());
      worst.add(*data_, reference.compute(q, dq), model_->dof());
    }
    worst.print(GetParam() + " vs " + label);
    return worst;
  }

  RobotDescription robot_;
  std::unique_ptr<Model> model_;
  std::unique_ptr<Data> data_;
};

TEST_P(ReferenceTest, MatchesKdl) {
  testing::KdlReference kdl(robot_.urdf_path.string(), robot_.base_frame, robot_.tcp_frame,
                            robot_.joints);
  const WorstError worst = worstAgainst(kdl, 1, "KDL");
  EXPECT_LE(worst.position, 1e-9);
  EXPECT_LE(worst.rotation, 1e-9);
  EXPECT_LE(worst.jacobian, 1e-9);
  EXPECT_LE(worst.gravity, 1e-9);
  EXPECT_LE(worst.coriolis, 1e-9);
  EXPECT_LE(worst.mass_matrix, 1e-9);
}

TEST_P(ReferenceTest, MatchesMujoco) {
  testing::MujocoReference mujoco(robot_.urdf_path.string(), robot_.tcp_frame, robot_.joints);
  const WorstError worst = worstAgainst(mujoco, 2, "MuJoCo");
  EXPECT_LE(worst.position, 1e-9);
  EXPECT_LE(worst.rotation, 1e-9);
  EXPECT_LE(worst.jacobian, 1e-9);
  EXPECT_LE(worst.gravity, 1e-9);
  // MuJoCo stores each inertia as principal moments + axes, rounded at ~1e-8 kg m^2.
  EXPECT_LE(worst.mass_matrix, 1e-7);
  EXPECT_LE(worst.coriolis, 1e-6);
}

INSTANTIATE_TEST_SUITE_P(Robots, ReferenceTest, ::testing::ValuesIn(testing::shippedRobots()),
                         [](const auto& param_info) { return param_info.param; });

}  // namespace
}  // namespace comply::model
