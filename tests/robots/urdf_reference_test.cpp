// The robot descriptions under robots/ reproduce the published parameters of each robot number for
// number, and each robot.yaml agrees with its URDF. The reference numbers live outside the project
// (COMPLY_REFERENCE_ROBOTS_DIR); only the comparison against them is skipped when they are absent.

#include <gtest/gtest.h>
#include <urdf_parser/urdf_parser.h>
#include <yaml-cpp/yaml.h>

#include <Eigen/Core>
#include <Eigen/Eigenvalues>
#include <algorithm>
#include <array>
#include <cmath>
#include <filesystem>
#include <map>
#include <optional>
#include <set>
#include <sstream>
#include <string>
#include <vector>

namespace {

namespace fs = std::filesystem;

const fs::path kRobotsDir = COMPLY_TEST_ROBOTS_DIR;
const fs::path kReferenceDir = COMPLY_TEST_REFERENCE_ROBOTS_DIR;
/// Every robot folder under robots/ (one with a robot.yaml): a robot added there is checked here
/// with no line to add.
std::vector<std::string> shippedRobots() {
  std::vector<std::string> names;
  for (const auto& entry : fs::directory_iterator(kRobotsDir)) {
    if (fs::is_regular_file(entry.path() / "robot.yaml")) {
      names.push_back(entry.path().filename().string());
    }
  }
  std::sort(names.begin(), names.end());
  return names;
}
const std::vector<std::string> kRobots = shippedRobots();

using Matrix3 = std::array<std::array<double, 3>, 3>;

// The references print up to 17 significant digits; anything coarser than 1e-12 means a number
// was retyped or rounded, not merely reparsed.
bool same(double actual, double expected) {
  const double difference = std::abs(actual - expected);
  return difference <= 1e-12 || difference <= 1e-12 * std::abs(expected);
}

std::string show(double value) {
  std::ostringstream out;
  out.precision(17);
  out << value;
  return out.str();
}

void expectSame(double actual, double expected, const std::string& where) {
  EXPECT_TRUE(same(actual, expected))
      << where << ": URDF has " << show(actual) << ", reference " << show(expected);
}

void expectSame(const urdf::Vector3& actual, const std::vector<double>& expected,
                const std::string& where) {
  ASSERT_EQ(expected.size(), 3u) << where << ": reference vector is not 3-long";
  expectSame(actual.x, expected[0], where + ".x");
  expectSame(actual.y, expected[1], where + ".y");
  expectSame(actual.z, expected[2], where + ".z");
}

// URDF fixed-axis roll-pitch-yaw: R = Rz(yaw) Ry(pitch) Rx(roll).
Matrix3 fromRpy(double roll, double pitch, double yaw) {
  const double cr = std::cos(roll), sr = std::sin(roll);
  const double cp = std::cos(pitch), sp = std::sin(pitch);
  const double cy = std::cos(yaw), sy = std::sin(yaw);
  return {{{cy * cp, cy * sp * sr - sy * cr, cy * sp * cr + sy * sr},
           {sy * cp, sy * sp * sr + cy * cr, sy * sp * cr - cy * sr},
           {-sp, cp * sr, cp * cr}}};
}

Matrix3 fromQuaternion(const urdf::Rotation& q) {
  const double x = q.x, y = q.y, z = q.z, w = q.w;
  return {{{1 - 2 * (y * y + z * z), 2 * (x * y - z * w), 2 * (x * z + y * w)},
           {2 * (x * y + z * w), 1 - 2 * (x * x + z * z), 2 * (y * z - x * w)},
           {2 * (x * z - y * w), 2 * (y * z + x * w), 1 - 2 * (x * x + y * y)}}};
}

// urdfdom keeps only a quaternion, and one rotation has two quaternions and many rpy triples, so
// rotations are compared as matrices.
void expectSameRotation(const urdf::Rotation& actual, const std::vector<double>& rpy,
                        const std::string& where) {
  ASSERT_EQ(rpy.size(), 3u) << where << ": reference rpy is not 3-long";
  const Matrix3 a = fromQuaternion(actual);
  const Matrix3 e = fromRpy(rpy[0], rpy[1], rpy[2]);
  for (int i = 0; i < 3; ++i) {
    for (int j = 0; j < 3; ++j) {
      EXPECT_NEAR(a[i][j], e[i][j], 1e-12)
          << where << ": rotation matrix entry (" << i << "," << j << ") differs";
    }
  }
}

/// The urdfdom joint type a reference file names.
int urdfType(const std::string& name) {
  static const std::map<std::string, int> kTypes = {
      {"revolute", urdf::Joint::REVOLUTE},   {"continuous", urdf::Joint::CONTINUOUS},
      {"prismatic", urdf::Joint::PRISMATIC}, {"floating", urdf::Joint::FLOATING},
      {"planar", urdf::Joint::PLANAR},       {"fixed", urdf::Joint::FIXED}};
  const auto found = kTypes.find(name);
  return found == kTypes.end() ? urdf::Joint::UNKNOWN : found->second;
}

bool isMovable(const urdf::Joint& joint) {
  return joint.type == urdf::Joint::REVOLUTE || joint.type == urdf::Joint::CONTINUOUS ||
         joint.type == urdf::Joint::PRISMATIC;
}

fs::path urdfPath(const std::string& robot) {
  return kRobotsDir / robot / (robot + ".urdf");
}

std::string robotName(const testing::TestParamInfo<std::string>& param) {
  return param.param;
}

std::vector<double> doubles(const YAML::Node& node) {
  return node.as<std::vector<double>>();
}

// Compares the URDF with the public reference numbers of the robot.
class UrdfReferenceTest : public testing::TestWithParam<std::string> {
 protected:
  void SetUp() override {
    const fs::path reference_file = kReferenceDir / (GetParam() + ".yaml");
    if (!fs::is_directory(kReferenceDir)) {
      GTEST_SKIP() << "reference data not found at " << kReferenceDir.string()
                   << "; set COMPLY_REFERENCE_ROBOTS_DIR";
    }
    if (!fs::is_regular_file(reference_file)) {
      GTEST_SKIP() << "reference data not found at " << reference_file.string()
                   << "; set COMPLY_REFERENCE_ROBOTS_DIR";
    }
    reference_ = YAML::LoadFile(reference_file.string());
    urdf_ = urdf::parseURDFFile(urdfPath(GetParam()).string());
    ASSERT_NE(urdf_, nullptr) << GetParam() << ": cannot parse " << urdfPath(GetParam());
  }

  std::string robot() const { return GetParam(); }

  /// check(expected, element, where) for each entry of the reference's `section` ("joints",
  /// "links"); `find` looks the entry's name up in the URDF, and an entry it lacks fails.
  template <typename Find, typename Check>
  void forEachEntry(const std::string& section, Find find, Check check) {
    ASSERT_TRUE(reference_[section].IsSequence());
    for (const YAML::Node& expected : reference_[section]) {
      const auto name = expected["name"].as<std::string>();
      // "joints" -> "joint": the messages name one element.
      const std::string where = robot() + " " + section.substr(0, section.size() - 1) + " " + name;
      if (const auto element = find(name)) {
        check(expected, *element, where);
      } else {
        ADD_FAILURE() << where << ": missing from the URDF";
      }
    }
  }

  YAML::Node reference_;
  urdf::ModelInterfaceSharedPtr urdf_;
};

TEST_P(UrdfReferenceTest, JointsMatchReference) {
  const auto find = [&](const std::string& name) { return urdf_->getJoint(name); };
  forEachEntry(
      "joints", find,
      [&](const YAML::Node& expected, const urdf::Joint& joint, const std::string& where) {
        const auto type = expected["type"].as<std::string>();
        EXPECT_EQ(joint.type, urdfType(type)) << where << ": type " << type;
        EXPECT_EQ(joint.parent_link_name, expected["parent"].as<std::string>())
            << where << ": parent";
        EXPECT_EQ(joint.child_link_name, expected["child"].as<std::string>()) << where << ": child";
        expectSame(joint.parent_to_joint_origin_transform.position, doubles(expected["origin_xyz"]),
                   where + " origin xyz");
        expectSameRotation(joint.parent_to_joint_origin_transform.rotation,
                           doubles(expected["origin_rpy"]), where + " origin rpy");
        if (type == "fixed") {
          return;
        }
        expectSame(joint.axis, doubles(expected["axis"]), where + " axis");
        const YAML::Node limits = expected["limits"];
        if (!joint.limits) {
          ADD_FAILURE() << where << ": no <limit> in the URDF";
          return;
        }
        if (type == "revolute" || type == "prismatic") {
          expectSame(joint.limits->lower, limits["lower"].as<double>(), where + " limit lower");
          expectSame(joint.limits->upper, limits["upper"].as<double>(), where + " limit upper");
        }
        expectSame(joint.limits->velocity, limits["velocity"].as<double>(),
                   where + " limit velocity");
        expectSame(joint.limits->effort, limits["effort"].as<double>(), where + " limit effort");
      });
}

TEST_P(UrdfReferenceTest, LinksMatchReference) {
  const auto find = [&](const std::string& name) { return urdf_->getLink(name); };
  forEachEntry(
      "links", find,
      [&](const YAML::Node& expected, const urdf::Link& link, const std::string& where) {
        const auto mass = expected["mass"].as<double>();
        if (mass == 0.0) {
          EXPECT_TRUE(!link.inertial || link.inertial->mass == 0.0)
              << where << ": a pure frame in the reference, but the URDF gives it mass";
          return;
        }
        if (!link.inertial) {
          ADD_FAILURE() << where << ": no <inertial> in the URDF";
          return;
        }
        const urdf::Inertial& inertial = *link.inertial;
        expectSame(inertial.mass, mass, where + " mass");
        expectSame(inertial.origin.position, doubles(expected["com_xyz"]), where + " com xyz");
        // The reference tensors are in link axes, so a rotated inertial frame would reinterpret
        // them.
        expectSameRotation(inertial.origin.rotation, {0.0, 0.0, 0.0}, where + " inertial rpy");
        const YAML::Node inertia = expected["inertia"];
        expectSame(inertial.ixx, inertia["ixx"].as<double>(), where + " ixx");
        expectSame(inertial.ixy, inertia["ixy"].as<double>(), where + " ixy");
        expectSame(inertial.ixz, inertia["ixz"].as<double>(), where + " ixz");
        expectSame(inertial.iyy, inertia["iyy"].as<double>(), where + " iyy");
        expectSame(inertial.iyz, inertia["iyz"].as<double>(), where + " iyz");
        expectSame(inertial.izz, inertia["izz"].as<double>(), where + " izz");
      });
}

// The URDF may only add the default TCP frame beyond the reference: anything else would be a
// parameter the reference cannot vouch for.
TEST_P(UrdfReferenceTest, AddsOnlyTheTcpFrame) {
  std::set<std::string> reference_joints;
  for (const YAML::Node& joint : reference_["joints"]) {
    reference_joints.insert(joint["name"].as<std::string>());
  }
  const auto tip = reference_["tip_link"].as<std::string>();
  int added = 0;
  for (const auto& [name, joint] : urdf_->joints_) {
    if (reference_joints.count(name) != 0) {
      continue;
    }
    ++added;
    const std::string where = robot() + " joint " + name;
    EXPECT_EQ(joint->type, urdf::Joint::FIXED) << where << ": not in the reference, must be fixed";
    EXPECT_EQ(joint->parent_link_name, tip) << where << ": must hang off the reference tip";
    expectSame(joint->parent_to_joint_origin_transform.position, {0.0, 0.0, 0.0},
               where + " origin xyz");
    expectSameRotation(joint->parent_to_joint_origin_transform.rotation, {0.0, 0.0, 0.0},
                       where + " origin rpy");
    const urdf::LinkConstSharedPtr child = urdf_->getLink(joint->child_link_name);
    ASSERT_NE(child, nullptr) << where << ": child link missing";
    EXPECT_TRUE(!child->inertial || child->inertial->mass == 0.0)
        << where << ": the default TCP frame must be massless";
  }
  EXPECT_EQ(added, 1) << robot() << ": expected exactly one joint beyond the reference (the TCP)";
  EXPECT_EQ(urdf_->getRoot()->name, reference_["base_link"].as<std::string>())
      << robot() << ": root link";
}

INSTANTIATE_TEST_SUITE_P(Robots, UrdfReferenceTest, testing::ValuesIn(kRobots), robotName);

// robot.yaml against its own URDF; needs no reference data.
class RobotConfigTest : public testing::TestWithParam<std::string> {
 protected:
  void SetUp() override {
    const fs::path file = kRobotsDir / GetParam() / "robot.yaml";
    ASSERT_TRUE(fs::is_regular_file(file)) << "missing " << file;
    config_ = YAML::LoadFile(file.string());
    ASSERT_TRUE(config_["urdf"]) << file << ": no 'urdf' key";
    const fs::path urdf_file = kRobotsDir / GetParam() / config_["urdf"].as<std::string>();
    urdf_ = urdf::parseURDFFile(urdf_file.string());
    ASSERT_NE(urdf_, nullptr) << GetParam() << ": cannot parse " << urdf_file;
    ASSERT_TRUE(config_["joints"].IsSequence()) << file << ": 'joints' is not a list";
    joints_ = config_["joints"].as<std::vector<std::string>>();
  }

  std::string robot() const { return GetParam(); }

  // Movable joints on the path from `base` down to `tip`, base first; nullopt if `base` is not
  // `tip` or one of its ancestors.
  std::optional<std::vector<std::string>> movableJointsBetween(const std::string& base,
                                                               const std::string& tip) const {
    std::vector<std::string> names;
    urdf::LinkConstSharedPtr link = urdf_->getLink(tip);
    while (link && link->name != base) {
      const urdf::JointSharedPtr joint = link->parent_joint;
      if (!joint) {
        return std::nullopt;
      }
      if (isMovable(*joint)) {
        names.push_back(joint->name);
      }
      link = urdf_->getLink(joint->parent_link_name);
    }
    if (!link) {
      return std::nullopt;
    }
    std::reverse(names.begin(), names.end());
    return names;
  }

  YAML::Node config_;
  urdf::ModelInterfaceSharedPtr urdf_;
  std::vector<std::string> joints_;
};

TEST_P(RobotConfigTest, NamesMatchTheFolder) {
  EXPECT_EQ(config_["name"].as<std::string>(), robot());
  EXPECT_EQ(config_["urdf"].as<std::string>(), robot() + ".urdf");
  EXPECT_TRUE(config_["description"] && config_["description"].IsScalar())
      << robot() << ": one-line description";
}

TEST_P(RobotConfigTest, JointsAreTheChainFromBaseToFlange) {
  const auto base = config_["base_frame"].as<std::string>();
  const auto flange = config_["flange_frame"].as<std::string>();
  const auto tcp = config_["tcp_frame"].as<std::string>();
  for (const auto& frame : {base, flange, tcp}) {
    EXPECT_NE(urdf_->getLink(frame), nullptr) << robot() << ": frame " << frame << " not in URDF";
  }
  for (const auto& name : joints_) {
    const urdf::JointConstSharedPtr joint = urdf_->getJoint(name);
    ASSERT_NE(joint, nullptr) << robot() << ": joint " << name << " not in URDF";
    EXPECT_TRUE(isMovable(*joint)) << robot() << ": joint " << name << " is not movable";
  }
  const auto chain = movableJointsBetween(base, flange);
  ASSERT_TRUE(chain) << robot() << ": " << flange << " does not descend from " << base;
  EXPECT_EQ(*chain, joints_) << robot() << ": 'joints' must be exactly the movable joints from "
                             << base << " to " << flange << ", base first";
  // A TCP behind a further movable joint would add a degree of freedom nobody controls.
  const auto tcp_chain = movableJointsBetween(flange, tcp);
  EXPECT_TRUE(tcp_chain && tcp_chain->empty())
      << robot() << ": tcp_frame " << tcp << " must be rigidly attached to " << flange;
}

TEST_P(RobotConfigTest, HomeIsWithinLimits) {
  const auto home = config_["home"].as<std::vector<double>>();
  ASSERT_EQ(home.size(), joints_.size()) << robot() << ": one home angle per joint";
  for (std::size_t i = 0; i < joints_.size(); ++i) {
    const urdf::JointConstSharedPtr joint = urdf_->getJoint(joints_[i]);
    ASSERT_NE(joint, nullptr) << robot() << ": joint " << joints_[i] << " not in URDF";
    if (joint->type == urdf::Joint::CONTINUOUS) {
      continue;
    }
    ASSERT_NE(joint->limits, nullptr) << robot() << ": joint " << joints_[i] << " has no limits";
    EXPECT_GE(home[i], joint->limits->lower) << robot() << ": home of " << joints_[i];
    EXPECT_LE(home[i], joint->limits->upper) << robot() << ": home of " << joints_[i];
  }
}

TEST_P(RobotConfigTest, PerJointParametersHaveOneEntryPerJoint) {
  const auto check = [&](const YAML::Node& section, const char* section_name, const char* key,
                         bool non_negative) {
    const std::string where = robot() + " " + section_name + "." + key;
    ASSERT_TRUE(section[key] && section[key].IsSequence()) << where << ": missing list";
    const auto values = section[key].as<std::vector<double>>();
    EXPECT_EQ(values.size(), joints_.size()) << where << ": one entry per joint";
    for (const double value : values) {
      EXPECT_TRUE(std::isfinite(value)) << where;
      if (non_negative) {
        EXPECT_GE(value, 0.0) << where;
      }
    }
  };
  if (const YAML::Node friction = config_["friction"]) {
    EXPECT_EQ(friction["model"].as<std::string>(), "sigmoid") << robot();
    check(friction, "friction", "phi1", false);
    check(friction, "friction", "phi2", false);
    check(friction, "friction", "phi3", false);
    EXPECT_TRUE(friction["source"]) << robot() << ": friction without a source";
  }
  if (const YAML::Node dynamics = config_["joint_dynamics"]) {
    check(dynamics, "joint_dynamics", "damping", true);
    check(dynamics, "joint_dynamics", "armature", true);
    check(dynamics, "joint_dynamics", "frictionloss", true);
    EXPECT_TRUE(dynamics["source"]) << robot() << ": joint_dynamics without a source";
  }
}

// Joint friction and damping belong to robot.yaml; a second copy in the URDF would be read by
// some tools (MuJoCo's URDF import) and not others.
TEST_P(RobotConfigTest, UrdfHasNoJointDynamics) {
  for (const auto& [name, joint] : urdf_->joints_) {
    EXPECT_EQ(joint->dynamics, nullptr) << robot() << ": joint " << name << " has <dynamics>";
  }
}

// MuJoCo (and any physical simulation) rejects an inertia whose principal moments are not
// positive or violate the triangle inequality.
TEST_P(RobotConfigTest, InertiasArePhysical) {
  for (const auto& [name, link] : urdf_->links_) {
    if (!link->inertial || link->inertial->mass == 0.0) {
      continue;
    }
    const urdf::Inertial& i = *link->inertial;
    EXPECT_GT(i.mass, 0.0) << robot() << " link " << name;
    Eigen::Matrix3d tensor;
    tensor << i.ixx, i.ixy, i.ixz, i.ixy, i.iyy, i.iyz, i.ixz, i.iyz, i.izz;
    const Eigen::Vector3d moments =
        Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d>(tensor, Eigen::EigenvaluesOnly)
            .eigenvalues();  // ascending
    EXPECT_GT(moments[0], 0.0) << robot() << " link " << name << ": not positive definite";
    EXPECT_GE(moments[0] + moments[1], moments[2] * (1.0 - 1e-12))
        << robot() << " link " << name << ": principal moments " << moments.transpose()
        << " violate the triangle inequality";
  }
}

INSTANTIATE_TEST_SUITE_P(Robots, RobotConfigTest, testing::ValuesIn(kRobots), robotName);

}  // namespace
