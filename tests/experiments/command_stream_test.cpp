// The experiments' command streams are task::CartesianSource implementations that always have a
// command (the simulation adapts them with `*stream.next(t, {})`) and name the time their motion
// ends, which the experiments' task files use as the last waypoint.

#include <gtest/gtest.h>

#include <cmath>
#include <stdexcept>

#include "connector_mating/mating_stream.hpp"
#include "connector_mating/peg_and_socket.hpp"
#include "surface_following/fixture.hpp"
#include "surface_following/surface_stream.hpp"

namespace comply::testing {
namespace {

namespace mating = experiments::connector_mating;
namespace surface = experiments::surface_following;

const Eigen::Quaterniond kPegDown(0.0, 1.0, 0.0, 0.0);  // TCP z pointing down

TEST(MatingStream, ApproachesStiffThenInsertsAlongTheSocketAxisInTheSocketFrame) {
  const Eigen::Vector3d home(0.3, 0.0, 0.5);
  const mating::Trial trial{"task_aligned", mating::ComplianceFrame::kSocket, 0.1};
  mating::MatingStream stream(trial, home, kPegDown, 10.0, 7);
  task::CartesianSource& source = stream;
  EXPECT_DOUBLE_EQ(source.motionEndTime(), 7.0);
  EXPECT_GT(mating::MatingStream::duration(), source.motionEndTime());

  const std::optional<CartesianCommand> start = source.next(0.0, {});
  ASSERT_TRUE(start.has_value());
  EXPECT_TRUE(start->position.isApprox(home));
  EXPECT_DOUBLE_EQ(start->stiffness_translational(0, 0), 3000.0);

  const std::optional<CartesianCommand> inserting = source.next(5.0, {});
  ASSERT_TRUE(inserting.has_value());
  EXPECT_DOUBLE_EQ(inserting->stamp_s, 5.0);
  EXPECT_DOUBLE_EQ(inserting->stiffness_translational(2, 2), 1000.0);
  EXPECT_DOUBLE_EQ(inserting->stiffness_rotational(0, 0), 10.0);
  // The stiff task axis is the socket axis, and the reference moves along it.
  EXPECT_TRUE((inserting->task_frame * Eigen::Vector3d::UnitZ()).isApprox(stream.axis()));
  const Eigen::Vector3d travel = source.next(6.0, {})->position - inserting->position;
  EXPECT_NEAR(travel.normalized().dot(mating::socketAxis(0.1)), 1.0, 1e-12);
}

/// The online conditions' insertion against a TCP that moves down a line tilted 10 deg from the
/// peg: the frame starts as the measured TCP's and turns onto the measured motion; the reference
/// sits on the TCP across that motion and leads it along; the orientation is held or follows.
TEST(MatingStream, OnlineFrameFollowsTheMeasuredMotionAndTheReferenceLeadsAlongIt) {
  const Eigen::Vector3d home(0.3, 0.0, 0.5);
  const double start_s = mating::MatingStream::insertionStart();
  const Eigen::Vector3d motion =
      Eigen::AngleAxisd(0.1745, Eigen::Vector3d::UnitX()) * Eigen::Vector3d(0.0, 0.0, -1.0);
  for (const bool oriented : {false, true}) {
    SCOPED_TRACE(oriented ? "online_fsf_oriented" : "online_fsf");
    const mating::Trial trial =
        mating::trialOf(oriented ? "online_fsf_oriented" : "online_fsf", 0.05);
    ASSERT_EQ(trial.frame, mating::ComplianceFrame::kOnlinePathFrame);
    mating::MatingStream stream(trial, home, kPegDown, 10.0, 7);
    MeasuredPose measured;
    measured.position = JointVector::Zero(7);
    measured.tcp_orientation = kPegDown;
    measured.valid = true;
    CartesianCommand command;
    for (int k = 0; k <= 100; ++k) {  // 1 s at 100 Hz, the TCP at 10 mm/s
      measured.tcp_position = home + 0.01 * 0.01 * k * motion;
      command = *stream.next(start_s + 0.01 * k, measured);
      if (k == 0) {
        EXPECT_TRUE(command.task_frame.isApprox(kPegDown));  // the TCP frame at first
      }
    }
    EXPECT_TRUE(stream.onlineRecords().back().tracking);
    const Eigen::Vector3d z = command.task_frame * Eigen::Vector3d::UnitZ();
    EXPECT_LT((z - motion).norm(), 1e-6);
    const Eigen::Vector3d lead = command.position - measured.tcp_position;
    EXPECT_LT((lead - lead.dot(z) * z).norm(), 1e-9);  // on the TCP across the motion
    EXPECT_GT(lead.dot(z), 0.0);                       // ahead along it
    EXPECT_DOUBLE_EQ(command.stiffness_translational(2, 2), 1000.0);
    EXPECT_DOUBLE_EQ(command.stiffness_translational(0, 0), 50.0);
    const Eigen::Vector3d peg = command.orientation * Eigen::Vector3d::UnitZ();
    EXPECT_LT((peg - (oriented ? motion : kPegDown * Eigen::Vector3d::UnitZ())).norm(), 1e-6);
    EXPECT_TRUE(stream.taskAxis(start_s + 1.0, kPegDown).isApprox(z));
  }
  EXPECT_THROW(mating::trialOf("online", 0.0), std::invalid_argument);
}

TEST(SurfaceStream, TaskAlignedFrameFollowsTheSurfaceFixedFrameStaysInTheBase) {
  const Eigen::Vector3d home(0.3, 0.2, 0.5);
  surface::SurfaceStream aligned({"task_aligned", true, false}, home, kPegDown, 0.02, 1.0, 7);
  surface::SurfaceStream fixed({"fixed_frame", false, false}, home, kPegDown, 0.02, 1.0, 7);
  EXPECT_DOUBLE_EQ(aligned.motionEndTime(), aligned.traverseEnd());
  EXPECT_GT(aligned.traverseEnd(), surface::SurfaceStream::traverseStart());

  const std::optional<CartesianCommand> start = aligned.next(0.0, {});
  ASSERT_TRUE(start.has_value());
  EXPECT_TRUE(start->position.isApprox(home));
  // Mid-traverse, on the bulge's slope: the compliant axis (task y) is the surface normal.
  const double t = 0.5 * (aligned.traverseStart() + aligned.traverseEnd()) - 1.0;
  const CartesianCommand on_slope = *aligned.next(t, {});
  const Eigen::Vector3d normal = on_slope.task_frame * Eigen::Vector3d::UnitY();
  EXPECT_NEAR(normal.z(), 0.0, 1e-9);
  EXPECT_GT(normal.y(), 0.9);            // out of the fixture, towards the probe
  EXPECT_GT(std::abs(normal.x()), 0.1);  // turned with the face, unlike base y
  EXPECT_TRUE(fixed.next(t, {})->task_frame.isApprox(Eigen::Quaterniond::Identity()));
}

}  // namespace
}  // namespace comply::testing
