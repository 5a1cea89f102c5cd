// Compliance frames against closed forms: the Frenet frame of a helix, the Darboux frame of a
// path on a sphere, and the behaviour where the Frenet normal is undefined (straight pieces) or
// flips (an inflection point).

#include "comply/task/frames.hpp"

#include <gtest/gtest.h>

#include <cmath>

#include "comply/task/path.hpp"

namespace comply::task {
namespace {

void expectOrthonormal(const Eigen::Matrix3d& frame) {
  EXPECT_LT((frame.transpose() * frame - Eigen::Matrix3d::Identity()).norm(), 1e-9);
  EXPECT_NEAR(frame.determinant(), 1.0, 1e-9);
}

TEST(FrenetFrame, HelixMatchesTheClosedForm) {
  // r(u) = (a cos u, a sin u, b u): T = (-a sin u, a cos u, b)/c, N = (-cos u, -sin u, 0),
  // B = (b sin u, -b cos u, a)/c with c = sqrt(a^2 + b^2).
  const double a = 0.2;
  const double b = 0.05;
  const double c = std::hypot(a, b);
  for (const double u : {0.0, 0.7, 2.0, 4.5}) {
    const Eigen::Vector3d velocity(-a * std::sin(u), a * std::cos(u), b);
    const Eigen::Vector3d acceleration(-a * std::cos(u), -a * std::sin(u), 0.0);
    const auto frame = frenetFrame(velocity, acceleration);
    ASSERT_TRUE(frame);
    expectOrthonormal(*frame);
    EXPECT_LT((frame->col(0) - velocity / c).norm(), 1e-12);
    EXPECT_LT((frame->col(1) - Eigen::Vector3d(-std::cos(u), -std::sin(u), 0.0)).norm(), 1e-12);
    EXPECT_LT((frame->col(2) - Eigen::Vector3d(b * std::sin(u), -b * std::cos(u), a) / c).norm(),
              1e-12);
  }
}

TEST(FrenetFrame, StraightLineUsesThePreviousOrFallbackNormal) {
  const Eigen::Vector3d along_x = Eigen::Vector3d::UnitX();
  const auto fallback =
      frenetFrame(along_x, Eigen::Vector3d::Zero(), std::nullopt, Eigen::Vector3d(0.3, 0.0, 1.0));
  ASSERT_TRUE(fallback);
  expectOrthonormal(*fallback);
  EXPECT_LT((fallback->col(1) - Eigen::Vector3d::UnitZ()).norm(), 1e-12);

  const auto kept = frenetFrame(along_x, Eigen::Vector3d::Zero(), Eigen::Vector3d::UnitY());
  ASSERT_TRUE(kept);
  EXPECT_LT((kept->col(1) - Eigen::Vector3d::UnitY()).norm(), 1e-12);

  // A fallback parallel to the tangent still gives a frame.
  const auto any = frenetFrame(Eigen::Vector3d::UnitZ(), Eigen::Vector3d::Zero());
  ASSERT_TRUE(any);
  expectOrthonormal(*any);

  EXPECT_FALSE(frenetFrame(Eigen::Vector3d::Zero(), Eigen::Vector3d::UnitY()));
}

TEST(FrenetFrame, TurnsSmoothlyThroughAnInflection) {
  // y = 0.03 sin(2 pi x / 0.18) has inflections at x = 0, 0.09, 0.18: the true principal normal
  // flips there; the streamed frame must not.
  std::vector<Eigen::Vector3d> points;
  for (int i = 0; i <= 1800; ++i) {
    const double x = 0.18 * i / 1800.0;
    points.emplace_back(x, 0.03 * std::sin(2.0 * M_PI * x / 0.18), 0.0);
  }
  const Path path(points);
  std::optional<Eigen::Vector3d> previous;
  double largest_turn = 0.0;
  for (double s = 0.0; s <= path.length(); s += 0.001) {
    const auto frame = frenetFrame(path.tangent(s), path.curvatureVector(s), previous);
    ASSERT_TRUE(frame);
    expectOrthonormal(*frame);
    if (previous) {
      largest_turn =
          std::max(largest_turn, std::acos(std::clamp(frame->col(1).dot(*previous), -1.0, 1.0)));
    }
    previous = frame->col(1);
  }
  // The tangent turns by at most ~0.12 rad per mm here; the normal follows, never jumps by pi.
  EXPECT_LT(largest_turn, 0.2);
}

TEST(DarbouxFrame, PathOnASphereHasTheRadialNormal) {
  // A circle of latitude on a unit sphere: tangent (-sin u, cos u, 0), normal = the point itself.
  const double latitude = 0.4;
  for (const double u : {0.0, 1.0, 3.0}) {
    const Eigen::Vector3d point(std::cos(latitude) * std::cos(u), std::cos(latitude) * std::sin(u),
                                std::sin(latitude));
    const Eigen::Vector3d tangent(-std::sin(u), std::cos(u), 0.0);
    const auto frame = darbouxFrame(2.0 * tangent, point);
    ASSERT_TRUE(frame);
    expectOrthonormal(*frame);
    EXPECT_LT((frame->col(0) - tangent).norm(), 1e-12);
    EXPECT_LT((frame->col(1) - point).norm(), 1e-12);
    EXPECT_LT((frame->col(2) - tangent.cross(point)).norm(), 1e-12);
  }
  // A normal that is not orthogonal to the tangent is made so.
  const auto tilted = darbouxFrame(Eigen::Vector3d::UnitX(), Eigen::Vector3d(0.5, 0.0, 1.0));
  ASSERT_TRUE(tilted);
  EXPECT_LT((tilted->col(1) - Eigen::Vector3d::UnitZ()).norm(), 1e-12);
  EXPECT_FALSE(darbouxFrame(Eigen::Vector3d::UnitX(), Eigen::Vector3d::UnitX()));
}

}  // namespace
}  // namespace comply::task
