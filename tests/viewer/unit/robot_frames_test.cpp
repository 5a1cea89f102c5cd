// A URDF's links placed from joint positions, against Orocos KDL's forward kinematics (the URDF
// read by urdfdom into a KDL tree by the test oracle, not by comply's code), for every robot.

#include "comply/viewer/robot_frames.hpp"

#include <gtest/gtest.h>

#include <fstream>
#include <map>
#include <random>
#include <sstream>

#include "comply/model/robot_description.hpp"
#include "kdl_reference.hpp"

namespace comply::viewer {
namespace {

std::string readText(const std::filesystem::path& path) {
  std::ifstream file(path);
  std::ostringstream text;
  text << file.rdbuf();
  return text.str();
}

/// `tip`'s pose in `base` composed from the transforms (each parent to child).
Eigen::Isometry3d compose(const std::vector<LinkTransform>& transforms, const std::string& base,
                          const std::string& tip) {
  std::map<std::string, const LinkTransform*> by_child;
  for (const LinkTransform& transform : transforms) {
    by_child[transform.child] = &transform;
  }
  Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
  for (std::string link = tip; link != base;) {
    const LinkTransform* transform = by_child.at(link);
    pose = transform->parent_to_child * pose;
    link = transform->parent;
  }
  return pose;
}

TEST(RobotFrames, EveryRobotsFlangeAgreesWithKdl) {
  std::mt19937 random(7);
  for (const std::string& name : model::availableRobots()) {
    const model::RobotDescription robot = model::loadRobotDescription(name);
    RobotFrames frames(readText(robot.urdf_path), robot.joints);
    const testing::KdlReference kdl(robot.urdf_path.string(), robot.base_frame, robot.flange_frame,
                                    robot.joints);
    for (int trial = 0; trial < 20; ++trial) {
      Eigen::VectorXd q(static_cast<Eigen::Index>(robot.joints.size()));
      std::uniform_real_distribution<double> angle(-2.0, 2.0);
      for (Eigen::Index i = 0; i < q.size(); ++i) {
        q[i] = angle(random);
      }
      frames.update(std::span<const double>(q.data(), static_cast<std::size_t>(q.size())));
      const Eigen::Isometry3d pose =
          compose(frames.transforms(), robot.base_frame, robot.flange_frame);
      const testing::ReferenceResult reference = kdl.compute(q, Eigen::VectorXd::Zero(q.size()));
      EXPECT_LT((pose.translation() - reference.position).norm(), 1e-12) << name;
      EXPECT_LT(Eigen::Quaterniond(pose.linear()).angularDistance(reference.orientation), 1e-9)
          << name;
    }
  }
}

TEST(RobotFrames, ItRefusesAJointNotInTheUrdfAndAUrdfThatDoesNotParse) {
  const model::RobotDescription robot = model::loadRobotDescription("fr3");
  const std::string urdf = readText(robot.urdf_path);
  try {
    RobotFrames frames(urdf, {"fr3_joint1", "elbow"});
    FAIL() << "accepted a joint the URDF lacks";
  } catch (const std::invalid_argument& error) {
    EXPECT_STREQ(error.what(), "joint \"elbow\" is not in the robot's URDF");
  }
  EXPECT_THROW(RobotFrames("<robot", robot.joints), std::invalid_argument);
}

}  // namespace
}  // namespace comply::viewer
