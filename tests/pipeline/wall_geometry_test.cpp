// Virtual walls as geometry (wall_geometry.hpp), against hand-computed numbers: which side is
// allowed, a commanded box's faces beside the file's, the projection of a point outside, the motion
// through a wall removed, and the barrier's force, its direction, size and that it only ever
// brakes.

#include "comply/pipeline/wall_geometry.hpp"

#include <gtest/gtest.h>

#include <cmath>

namespace comply::pipeline {
namespace {

// A wall at x = 0.5 (allowed: x <= 0.5) and the box [0, 1] x [-0.2, 0.2] x [0.1, 0.9].
WallSet wallAndBox() {
  WallSet set;
  EXPECT_TRUE(compileWalls({WallPlane{{0.5, 0.0, 0.0}, {1.0, 0.0, 0.0}}},
                           {WallBox{{0.0, -0.2, 0.1}, {1.0, 0.2, 0.9}}}, set));
  return set;
}

constexpr BarrierGains kGains{0.05, 2000.0, 200.0};

TEST(WallGeometry, ABoxIsItsSixFacesWithOutwardNormals) {
  const WallSet set = wallAndBox();
  ASSERT_EQ(set.count, 7);
  EXPECT_DOUBLE_EQ(nearestWallDistance(set, {0.4, 0.0, 0.5}), 0.1);     // the wall
  EXPECT_DOUBLE_EQ(nearestWallDistance(set, {0.2, 0.15, 0.5}), 0.05);   // the box's +y face
  EXPECT_DOUBLE_EQ(nearestWallDistance(set, {0.2, 0.0, 0.05}), -0.05);  // below its floor
  EXPECT_TRUE(std::isinf(nearestWallDistance(WallSet{}, {0.0, 0.0, 0.0})));
}

TEST(WallGeometry, TooManyPlanesAreRefused) {
  WallSet set;
  EXPECT_FALSE(compileWalls({}, std::vector<WallBox>(kMaxWallPlanes / 6 + 1), set));
  EXPECT_EQ(set.count, 0);
}

TEST(WallGeometry, ACommandedBoxFitsBesidesAFullFileSet) {
  // The file's limit of planes, then a commanded box's six faces on top.
  WallSet set;
  ASSERT_TRUE(compileWalls({}, std::vector<WallBox>(kMaxWallPlanes / 6), set));
  ASSERT_EQ(set.count, kMaxWallPlanes);
  const WallBox box{{0.1, -0.2, 0.3}, {0.6, 0.2, 0.8}};
  ASSERT_TRUE(appendBox(box, set));
  EXPECT_EQ(set.count, kMaxWallPlanes + 6);
  EXPECT_EQ(set.planes[kMaxWallPlanes].point, box.max);
  EXPECT_EQ(set.planes[kMaxWallPlanes].normal, Eigen::Vector3d::UnitX());
  EXPECT_EQ(set.planes[kMaxWallPlanes + 5].point, box.min);
  EXPECT_EQ(set.planes[kMaxWallPlanes + 5].normal, -Eigen::Vector3d::UnitZ());
  // No room for another: refused, the set unchanged.
  EXPECT_FALSE(appendBox(box, set));
  EXPECT_EQ(set.count, kMaxWallPlanes + 6);
}

TEST(WallGeometry, APointOutsideIsProjectedOntoTheNearestFaces) {
  const WallSet set = wallAndBox();
  Eigen::Vector3d inside(0.3, 0.1, 0.5);
  EXPECT_FALSE(projectInside(set, inside));
  EXPECT_EQ(inside, Eigen::Vector3d(0.3, 0.1, 0.5));
  // Past the wall and out of the box at a corner: onto the wall and the box's +y face and floor.
  Eigen::Vector3d outside(0.7, 0.3, -0.2);
  EXPECT_TRUE(projectInside(set, outside));
  EXPECT_NEAR((outside - Eigen::Vector3d(0.5, 0.2, 0.1)).norm(), 0.0, 1e-15);
  // Two walls at 45 degrees to each other: the result is inside both.
  WallSet wedge;
  ASSERT_TRUE(compileWalls({WallPlane{{0.0, 0.0, 0.0}, {0.0, 0.0, 1.0}},
                            WallPlane{{0.0, 0.0, 0.0}, {std::sqrt(0.5), 0.0, std::sqrt(0.5)}}},
                           {}, wedge));
  Eigen::Vector3d p(0.3, 0.0, 0.2);
  EXPECT_TRUE(projectInside(wedge, p));
  EXPECT_GE(nearestWallDistance(wedge, p), -1e-9);
}

TEST(WallGeometry, MotionOutThroughAWallIsRemovedOnlyOnIt) {
  const WallSet set = wallAndBox();
  Eigen::Vector3d v(0.5, 0.1, -0.2);
  // On the wall: the +x part goes, the rest stays.
  EXPECT_TRUE(removeOutward(set, {0.5, 0.0, 0.5}, 1e-9, v));
  EXPECT_EQ(v, Eigen::Vector3d(0.0, 0.1, -0.2));
  // Away from every wall, or moving inward: untouched.
  Eigen::Vector3d w(0.5, 0.1, -0.2);
  EXPECT_FALSE(removeOutward(set, {0.3, 0.0, 0.5}, 1e-9, w));
  Eigen::Vector3d in(-0.5, 0.0, 0.0);
  EXPECT_FALSE(removeOutward(set, {0.5, 0.0, 0.5}, 1e-9, in));
  // Two vectors at once: each as it would be alone, whichever of them points out.
  Eigen::Vector3d velocity(-0.5, 0.1, 0.0);
  Eigen::Vector3d acceleration(2.0, 0.0, 1.0);
  EXPECT_TRUE(removeOutward(set, {0.5, 0.0, 0.5}, 1e-9, velocity, acceleration));
  EXPECT_EQ(velocity, Eigen::Vector3d(-0.5, 0.1, 0.0));
  EXPECT_EQ(acceleration, Eigen::Vector3d(0.0, 0.0, 1.0));
  Eigen::Vector3d away(0.5, 0.0, 0.0);
  Eigen::Vector3d also(0.0, 0.0, -3.0);
  EXPECT_FALSE(removeOutward(set, {0.3, 0.0, 0.5}, 1e-9, away, also));
}

TEST(WallGeometry, TheBarrierBrakesAnApproachAlongTheInwardNormal) {
  const WallSet set = wallAndBox();
  // 20 mm from the wall (30 mm into the 50 mm zone) at 0.5 m/s toward it:
  // F = -(2000 x 0.03 x 1 + 200 x 0.5) = -160 N along x.
  double nearest_m = 0.0;
  const Eigen::Vector3d force =
      barrierForce(set, kGains, {0.48, 0.0, 0.5}, {0.5, 0.0, 0.0}, &nearest_m);
  EXPECT_NEAR(force.x(), -160.0, 1e-9);
  EXPECT_DOUBLE_EQ(nearest_m, nearestWallDistance(set, {0.48, 0.0, 0.5}));
  EXPECT_EQ(force.y(), 0.0);
  EXPECT_EQ(force.z(), 0.0);
  // Slower than the engage speed the spring fades: at 0.01 m/s, half of it plus the damping.
  EXPECT_NEAR(barrierForce(set, kGains, {0.48, 0.0, 0.5}, {0.01, 0.0, 0.0}).x(),
              -(2000.0 * 0.03 * 0.5 + 200.0 * 0.01), 1e-9);
  // Past the wall the depth keeps growing: 10 mm past, 60 mm in.
  EXPECT_NEAR(barrierForce(set, kGains, {0.51, 0.0, 0.5}, {0.5, 0.0, 0.0}).x(),
              -(2000.0 * 0.06 + 200.0 * 0.5), 1e-9);
}

TEST(WallGeometry, TheBarrierIsSilentAwayFromAWallAtRestOrLeaving) {
  const WallSet set = wallAndBox();
  EXPECT_TRUE(barrierForce(set, kGains, {0.4, 0.0, 0.5}, {0.5, 0.0, 0.0}).isZero(0.0));   // far
  EXPECT_TRUE(barrierForce(set, kGains, {0.48, 0.0, 0.5}, {0.0, 0.0, 0.0}).isZero(0.0));  // rest
  EXPECT_TRUE(barrierForce(set, kGains, {0.48, 0.0, 0.5}, {-0.5, 0.0, 0.0}).isZero(0.0));
  // Sliding along the wall is not braked.
  EXPECT_TRUE(barrierForce(set, kGains, {0.48, 0.0, 0.5}, {0.0, 0.0, 0.5}).isZero(0.0));
}

TEST(WallGeometry, TheBarrierOnlyEverTakesEnergyOut) {
  const WallSet set = wallAndBox();
  for (int i = 0; i < 1000; ++i) {
    const Eigen::Vector3d p(0.4 + 0.15 * std::sin(0.37 * i), 0.2 * std::cos(0.11 * i),
                            0.1 + 0.8 * std::abs(std::sin(0.05 * i)));
    const Eigen::Vector3d v(std::sin(0.7 * i), std::cos(1.3 * i), std::sin(2.1 * i));
    EXPECT_LE(barrierForce(set, kGains, p, v).dot(v), 0.0) << i;
  }
}

}  // namespace
}  // namespace comply::pipeline
