// The model's branch-free sin/cos against libm: within a few ulp over the range it serves, at the
// quadrant boundaries where the reduction switches, and for large but allowed angles.

#include "../../src/model/joint_trig.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <random>
#include <vector>

namespace comply::model {
namespace {

constexpr double kUlp = 2.220446049250313e-16;

void expectCloseToLibm(const std::vector<double>& angles) {
  std::vector<double> s(angles.size());
  std::vector<double> c(angles.size());
  jointSinCos(angles.data(), static_cast<int>(angles.size()), s.data(), c.data());
  for (std::size_t i = 0; i < angles.size(); ++i) {
    // Absolute, in units of the ulp of 1: sin and cos are bounded by 1, and near their zeros a
    // relative bound would test the reduction of pi itself, which no double can hold.
    const double tolerance = 4.0 * kUlp * std::max(1.0, std::abs(angles[i]) * 1e-5);
    EXPECT_NEAR(s[i], std::sin(angles[i]), tolerance) << "q = " << angles[i];
    EXPECT_NEAR(c[i], std::cos(angles[i]), tolerance) << "q = " << angles[i];
  }
}

TEST(JointSinCos, AgreesWithLibmOverTheJointRange) {
  std::mt19937 rng(1);
  std::uniform_real_distribution<double> angle(-2.0 * std::numbers::pi, 2.0 * std::numbers::pi);
  std::vector<double> angles(10000);
  for (double& q : angles) {
    q = angle(rng);
  }
  expectCloseToLibm(angles);
}

TEST(JointSinCos, AgreesAtTheQuadrantBoundaries) {
  std::vector<double> angles;
  for (int k = -8; k <= 8; ++k) {
    const double boundary = k * std::numbers::pi / 4.0;
    for (const double offset : {-1e-9, -1e-15, 0.0, 1e-15, 1e-9}) {
      angles.push_back(boundary + offset);
    }
  }
  expectCloseToLibm(angles);
}

TEST(JointSinCos, AgreesForLargeAllowedAngles) {
  std::mt19937 rng(2);
  std::uniform_real_distribution<double> angle(-kFastTrigLimit, kFastTrigLimit);
  std::vector<double> angles(10000);
  for (double& q : angles) {
    q = angle(rng);
  }
  expectCloseToLibm(angles);
}

}  // namespace
}  // namespace comply::model
