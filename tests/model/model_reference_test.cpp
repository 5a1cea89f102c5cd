// The model against two independent implementations on every shipped robot: KDL (urdfdom ->
// KDL::Tree conversion in tests/support) and MuJoCo (its own URDF importer, fixed frames kept).

#include <gtest/gtest.h>

#include <string>

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
