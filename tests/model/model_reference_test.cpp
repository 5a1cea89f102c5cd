// The model against two independent implementations on every shipped robot: KDL (urdfdom ->
// KDL::Tree conversion in tests/support) and MuJoCo (its own URDF importer, fixed frames kept).

#include <gtest/gtest.h>

#include <memory>
#include <string>
#include <vector>

#include "comply/model/robot_description.hpp"
#include "comply/model/update.hpp"
#include "kdl_reference.hpp"
#include "max_error.hpp"
#include "mujoco_reference.hpp"
#include "robot_sampling.hpp"

namespace comply::model {
namespace {

constexpr int kSamples = 1000;

/// The model's results in the references' form.
testing::ReferenceResult resultOf(const Data& data) {
  return {.position = data.tip_position,
          .orientation = data.tip_orientation,
          .jacobian = data.jacobian,
          .gravity = data.gravity,
          .coriolis = data.coriolis,
          .mass_matrix = data.mass_matrix};
}

class ReferenceTest : public testing::ShippedRobotTest {
 protected:
  /// The worst errors against `reference` (its compute(q, dq)) over kSamples joint samples of
  /// seed `seed`.
  template <typename Reference>
  testing::MaxError worstAgainst(Reference& reference, unsigned seed, const std::string& label) {
    testing::JointSampler sampler(*model_, seed);
    testing::MaxError worst;
    for (int i = 0; i < kSamples; ++i) {
      const testing::JointSample sample = sampler.next();
      EXPECT_EQ(update(*model_, *data_, sample.q, sample.dq, Quantity::kAll), UpdateStatus::kOk);
      const Eigen::VectorXd q = Eigen::Map<const Eigen::VectorXd>(sample.q.data(), sample.q.size());
      const Eigen::VectorXd dq =
          Eigen::Map<const Eigen::VectorXd>(sample.dq.data(), sample.dq.size());
      worst.add(resultOf(*data_), reference.compute(q, dq));
    }
    worst.print(GetParam() + " vs " + label + ", " + std::to_string(kSamples) + " samples,");
    return worst;
  }
};

TEST_P(ReferenceTest, MatchesKdl) {
  testing::KdlReference kdl(robot_.urdf_path.string(), robot_.base_frame, robot_.tcp_frame,
                            robot_.joints);
  worstAgainst(kdl, 1, "KDL").expectWithin(1e-9, 1e-9);
}

/// `reference` with the rotor inertias added to its M's diagonal: what a model built with them
/// (ModelOptions::armature) must equal.
template <typename Reference>
struct WithArmature {
  Reference& reference;
  Eigen::VectorXd armature;
  testing::ReferenceResult compute(const Eigen::VectorXd& q, const Eigen::VectorXd& dq) {
    testing::ReferenceResult result = reference.compute(q, dq);
    result.mass_matrix.diagonal() += armature;
    return result;
  }
};

TEST_P(ReferenceTest, WithTheRotorInertiasMatchesKdlsMassMatrixPlusThem) {
  ASSERT_TRUE(robot_.joint_dynamics.has_value());
  const std::vector<double>& armature = robot_.joint_dynamics->armature;
  model::ModelOptions options = robot_.modelOptions();
  options.armature = armature;
  model_ = std::make_unique<Model>(robot_.loadModel(options));
  data_ = std::make_unique<Data>(*model_);
  testing::KdlReference kdl(robot_.urdf_path.string(), robot_.base_frame, robot_.tcp_frame,
                            robot_.joints);
  WithArmature<testing::KdlReference> geared{
      kdl, Eigen::Map<const Eigen::VectorXd>(armature.data(),
                                             static_cast<Eigen::Index>(armature.size()))};
  worstAgainst(geared, 3, "KDL + armature").expectWithin(1e-9, 1e-9);
}

TEST_P(ReferenceTest, MatchesMujoco) {
  testing::MujocoReference mujoco(robot_.urdf_path.string(), robot_.tcp_frame, robot_.joints);
  const testing::MaxError worst = worstAgainst(mujoco, 2, "MuJoCo");
  // MuJoCo stores each inertia as principal moments + axes, rounded at ~1e-8 kg m^2.
  worst.expectWithin(1e-9, 1e-6);
  EXPECT_LE(worst.mass_matrix, 1e-7);
}

INSTANTIATE_TEST_SUITE_P(Robots, ReferenceTest, ::testing::ValuesIn(testing::shippedRobots()),
                         [](const auto& param_info) { return param_info.param; });

}  // namespace
}  // namespace comply::model
