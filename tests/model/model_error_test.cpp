// Every way a model can be asked for wrongly gives a named error, never a crash.

#include "comply/model/model_error.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <limits>

#include "comply/model/update.hpp"
#include "test_urdfs.hpp"

namespace comply::model {
namespace {

ModelOptions options(std::vector<std::string> joints, const std::string& tip,
                     const std::string& base = {}) {
  ModelOptions result;
  result.joint_names = std::move(joints);
  result.tip_frame = tip;
  result.base_frame = base;
  return result;
}

/// Runs `load`, expects a ModelError with `code` whose message contains every `fragment`.
template <typename Load>
void expectModelError(Load load, ModelErrc code, const std::vector<std::string>& fragments) {
  try {
    load();
    FAIL() << "expected " << toString(code);
  } catch (const ModelError& error) {
    EXPECT_EQ(error.code(), code) << error.what();
    const std::string message = error.what();
    EXPECT_NE(message.find(std::string(toString(code))), std::string::npos) << message;
    for (const auto& fragment : fragments) {
      EXPECT_NE(message.find(fragment), std::string::npos)
          << "'" << fragment << "' not in: " << message;
    }
  }
}

TEST(ModelErrorTest, MissingFile) {
  expectModelError([] { Model::fromUrdfFile("/nonexistent/robot.urdf", options({"a"}, "tip")); },
                   ModelErrc::kFileNotFound, {"/nonexistent/robot.urdf"});
}

TEST(ModelErrorTest, InvalidXml) {
  expectModelError([] { Model::fromUrdfString("<robot name='x'><link", options({"a"}, "t")); },
                   ModelErrc::kInvalidUrdf, {});
  const auto path = std::filesystem::temp_directory_path() / "comply_invalid.urdf";
  std::ofstream(path) << "not xml at all";
  expectModelError([&] { Model::fromUrdfFile(path, options({"a"}, "t")); }, ModelErrc::kInvalidUrdf,
                   {path.string()});
  std::filesystem::remove(path);
}

TEST(ModelErrorTest, KinematicLoopIsRefusedNotWalkedForever) {
  // urdfdom accepts this (the root is `base`); walking up from b used to never end.
  const std::string loop = test_urdfs::kinematicLoop();
  expectModelError([&] { Model::fromUrdfString(loop, options({"j1"}, "b")); },
                   ModelErrc::kInvalidUrdf, {"kinematic loop", "a URDF must be a tree"});
}

// One revolute joint moving link `arm`; `inertial` and `limit` are spliced in.
std::string oneJoint(const std::string& inertial, const std::string& limit) {
  return R"(<robot name="one"><link name="base"/><link name="arm">)" + inertial +
         R"(</link><joint name="j" type="revolute"><parent link="base"/><child link="arm"/>
         <axis xyz="0 0 1"/>)" +
         limit + "</joint></robot>";
}

std::string inertial(double mass, double ixx, double iyy, double izz) {
  return "<inertial><mass value=\"" + std::to_string(mass) + "\"/><inertia ixx=\"" +
         std::to_string(ixx) + "\" ixy=\"0\" ixz=\"0\" iyy=\"" + std::to_string(iyy) +
         "\" iyz=\"0\" izz=\"" + std::to_string(izz) + "\"/></inertial>";
}

TEST(ModelErrorTest, NonPhysicalRobotsAreRefused) {
  const std::string limit = R"(<limit lower="-1" upper="1" velocity="1" effort="10"/>)";
  const auto load = [](const std::string& urdf) {
    return [urdf] { Model::fromUrdfString(urdf, options({"j"}, "arm")); };
  };
  EXPECT_NO_THROW(load(oneJoint(inertial(1.0, 0.01, 0.01, 0.01), limit))());
  expectModelError(load(oneJoint("", limit)), ModelErrc::kInvalidInertia,
                   {"joint 'j' moves no mass", "'arm'"});
  expectModelError(load(oneJoint(inertial(0.0, 0.0, 0.0, 0.0), limit)), ModelErrc::kInvalidInertia,
                   {"moves no mass"});
  // A mass without rotational inertia (a point mass): MuJoCo refuses it, and so does comply.
  expectModelError(load(oneJoint(inertial(1.0, 0.0, 0.0, 0.0), limit)), ModelErrc::kInvalidInertia,
                   {"joint 'j' moves a body without rotational inertia", "link 'arm'"});
  expectModelError(load(oneJoint(inertial(1e12, 1.0, 1.0, 1.0), limit)), ModelErrc::kInvalidInertia,
                   {"link 'arm'", "more than any arm's link"});
  expectModelError(load(oneJoint(inertial(1.0, 0.01, 0.01, 0.03), limit)),
                   ModelErrc::kInvalidInertia, {"link 'arm'", "non-physical inertia"});
  expectModelError(load(oneJoint(inertial(1.0, -0.01, 0.01, 0.01), limit)),
                   ModelErrc::kInvalidInertia, {"non-physical inertia"});
  expectModelError(load(oneJoint(inertial(1.0, 0.01, 0.01, 0.01),
                                 R"(<limit lower="1" upper="-1" velocity="1" effort="10"/>)")),
                   ModelErrc::kInvalidUrdf, {"joint 'j'", "lower limit", "above its upper limit"});
}

// Two revolute joints: j1 moves link `middle` (`middle_inertial` spliced in), j2 moves `arm`
// (`arm_inertial` spliced in).
std::string twoJoints(const std::string& middle_inertial, const std::string& arm_inertial) {
  const std::string limit = R"(<axis xyz="0 0 1"/>
    <limit lower="-1" upper="1" velocity="1" effort="10"/>)";
  return R"(<robot name="two"><link name="base"/><link name="middle">)" + middle_inertial +
         R"(</link><link name="arm">)" + arm_inertial +
         R"(</link><joint name="j1" type="revolute"><parent link="base"/><child link="middle"/>
         <origin xyz="0 0 0.1"/>)" +
         limit + R"(</joint><joint name="j2" type="revolute"><parent link="middle"/>
         <child link="arm"/><origin xyz="0.3 0 0"/>)" +
         limit + "</joint></robot>";
}

TEST(ModelErrorTest, EveryMovingBodyHasAMass) {
  // A massless link between two controlled joints is what urdfdom leaves of an <inertial> it
  // could not read, and MuJoCo refuses to simulate it: `validate` must refuse it as `sim` does.
  const auto massive = inertial(1.0, 0.01, 0.01, 0.01);
  const auto load = [](const std::string& urdf) {
    return [urdf] { Model::fromUrdfString(urdf, options({"j1", "j2"}, "arm")); };
  };
  EXPECT_NO_THROW(load(twoJoints(massive, massive))());
  expectModelError(load(twoJoints("", massive)), ModelErrc::kInvalidInertia,
                   {"joint 'j1' moves no mass", "link 'middle'"});
  expectModelError(load(twoJoints(inertial(0.0, 0.0, 0.0, 0.0), massive)),
                   ModelErrc::kInvalidInertia, {"joint 'j1' moves no mass", "link 'middle'"});
  expectModelError(load(twoJoints(massive, "")), ModelErrc::kInvalidInertia,
                   {"joint 'j2' moves no mass", "link 'arm'"});
}

TEST(ModelErrorTest, AMasslessLinkCarryingAMassiveOneIsOneBody) {
  // Mass is lumped across fixed joints: the body of j1 is `middle` and the link fixed to it, so a
  // massless `middle` carrying 1 kg 0.15 m along x is a 1 kg body (MuJoCo accepts it too).
  std::string urdf = twoJoints("", inertial(1.0, 0.01, 0.01, 0.01));
  urdf.replace(urdf.find("</robot>"), 8,
               "<link name=\"payload\">" + inertial(1.0, 0.01, 0.01, 0.01) + R"(</link>
    <joint name="middle_to_payload" type="fixed"><parent link="middle"/><child link="payload"/>
      <origin xyz="0.15 0 0"/></joint></robot>)");
  const Model model = Model::fromUrdfString(urdf, options({"j1", "j2"}, "arm"));
  EXPECT_EQ(model.body(0).mass_kg, 1.0);
  EXPECT_NEAR((model.body(0).com - Eigen::Vector3d(0.15, 0.0, 0.0)).norm(), 0.0, 1e-12);
}

// twoJoints with the <inertial> of `middle` written out, `from` replaced by `to` in its text.
std::string middleWritten(const std::string& from, const std::string& to) {
  std::string written = R"(<inertial><origin xyz="0.1 0 0" rpy="0 0 0"/><mass value="1"/>
    <inertia ixx="0.01" ixy="0" ixz="0" iyy="0.01" iyz="0" izz="0.01"/></inertial>)";
  written.replace(written.find(from), from.size(), to);
  return twoJoints(written, inertial(1.0, 0.01, 0.01, 0.01));
}

TEST(ModelErrorTest, AnInertialValueUrdfdomCannotReadIsRefused) {
  // urdfdom logs such a value and reads the mass, the inertia or both as zero: the model used to
  // be built from numbers nobody wrote (gravity off by 1.45 N m on the FR3's joint 2).
  struct Case {
    std::string from, to, complaint;
  };
  const std::vector<Case> cases{
      {R"(value="1")", R"(value="nan")", R"(<mass value="nan">: not a finite number)"},
      {R"(value="1")", R"(value="inf")", R"(<mass value="inf">: not a finite number)"},
      {R"(value="1")", R"(value="abc")", R"(<mass value="abc">: not a number)"},
      {R"(ixx="0.01")", R"(ixx="nan")", R"(<inertia ixx="nan">: not a finite number)"},
      {R"(iyy="0.01")", R"(iyy="-inf")", R"(<inertia iyy="-inf">: not a finite number)"},
      {R"(xyz="0.1 0 0")", R"(xyz="0.1 nan 0")",
       R"(<origin xyz="0.1 nan 0">: not three finite numbers)"},
      // Read by a lenient parser, zero to urdfdom:
      {R"(value="1")", R"(value="1 ")", R"(<mass value="1 ">: not a number)"},
      {R"(value="1")", R"(value="+-1")", R"(<mass value="+-1">: not a number)"},
      {R"(value="1")", R"(value="1e400")", R"(<mass value="1e400">: out of a double's range)"},
      {R"(rpy="0 0 0")", R"(rpy="0 0")", R"(<origin rpy="0 0">: not three finite numbers)"},
      {R"( ixz="0")", "", "<inertial> has no <inertia ixz>"},
      {R"(<mass value="1"/>)", "", "<inertial> has no <mass value>"},
  };
  for (const auto& [from, to, complaint] : cases) {
    SCOPED_TRACE(to);
    expectModelError(
        [&] {
          Model::fromUrdfString(middleWritten(from, to), options({"j1", "j2"}, "arm"));
        },
        ModelErrc::kInvalidInertia, {"link 'middle': " + complaint});
  }
  // What urdfdom reads alike is accepted: a leading '+' or blank, blanks between components.
  EXPECT_NO_THROW(Model::fromUrdfString(middleWritten(R"(value="1")", R"(value=" +1")"),
                                        options({"j1", "j2"}, "arm")));
  EXPECT_NO_THROW(Model::fromUrdfString(middleWritten(R"(xyz="0.1 0 0")", R"(xyz=" 0.1  0 0 ")"),
                                        options({"j1", "j2"}, "arm")));
}

TEST(ModelErrorTest, AnUnreadableInertialNamesTheFile) {
  const auto path = std::filesystem::temp_directory_path() / "comply_nan_mass.urdf";
  std::ofstream(path) << middleWritten(R"(value="1")", R"(value="nan")");
  expectModelError(
      [&] {
        Model::fromUrdfFile(path, options({"j1", "j2"}, "arm"));
      },
      ModelErrc::kInvalidInertia,
      {path.string(), R"(link 'middle': <mass value="nan">: not a finite number)"});
  std::filesystem::remove(path);
}

TEST(ModelErrorTest, UnknownJointsAreAllListed) {
  expectModelError(
      [] {
        Model::fromUrdfString(test_urdfs::planarTwoLink(),
                              options({"shoulder", "knee", "ankle"}, "tip"));
      },
      ModelErrc::kUnknownJoint, {"knee", "ankle"});
}

TEST(ModelErrorTest, MissingChainJoint) {
  expectModelError(
      [] { Model::fromUrdfString(test_urdfs::planarTwoLink(), options({"shoulder"}, "tip")); },
      ModelErrc::kMissingJoint, {"elbow"});
}

TEST(ModelErrorTest, DuplicateJoint) {
  expectModelError(
      [] {
        Model::fromUrdfString(test_urdfs::planarTwoLink(),
                              options({"shoulder", "elbow", "shoulder"}, "tip"));
      },
      ModelErrc::kDuplicateJoint, {"shoulder"});
}

TEST(ModelErrorTest, JointOutsideTheChain) {
  // Tip at link1: the elbow exists but is not between base and tip.
  expectModelError(
      [] {
        Model::fromUrdfString(test_urdfs::planarTwoLink(), options({"shoulder", "elbow"}, "link1"));
      },
      ModelErrc::kJointNotInChain, {"elbow"});
}

TEST(ModelErrorTest, UnknownFrames) {
  expectModelError(
      [] {
        Model::fromUrdfString(test_urdfs::planarTwoLink(), options({"shoulder", "elbow"}, "hand"));
      },
      ModelErrc::kUnknownFrame, {"hand"});
  expectModelError(
      [] {
        Model::fromUrdfString(test_urdfs::planarTwoLink(),
                              options({"shoulder", "elbow"}, "tip", "world"));
      },
      ModelErrc::kUnknownFrame, {"world"});
  expectModelError(
      [] { Model::fromUrdfString(test_urdfs::planarTwoLink(), options({"shoulder"}, "")); },
      ModelErrc::kUnknownFrame, {"tip frame"});
}

TEST(ModelErrorTest, TipAboveBase) {
  expectModelError(
      [] { Model::fromUrdfString(test_urdfs::planarTwoLink(), options({}, "base", "link2")); },
      ModelErrc::kFrameNotInChain, {"base", "link2"});
}

TEST(ModelErrorTest, FloatingAndPlanarJointsAreRejected) {
  for (const std::string type : {"floating", "planar"}) {
    expectModelError(
        [&] { Model::fromUrdfString(test_urdfs::withJointType(type), options({"hinge"}, "tip")); },
        ModelErrc::kUnsupportedJoint, {"odd_joint", type});
  }
}

TEST(ModelErrorTest, TooManyJoints) {
  std::vector<std::string> names;
  for (int i = 0; i <= kMaxDof; ++i) {
    names.push_back("j" + std::to_string(i));
  }
  expectModelError(
      [&] {
        Model::fromUrdfString(test_urdfs::longChain(kMaxDof + 1),
                              options(names, "l" + std::to_string(kMaxDof + 1)));
      },
      ModelErrc::kTooManyJoints, {std::to_string(kMaxDof + 1)});
  names.pop_back();
  const Model at_limit = Model::fromUrdfString(test_urdfs::longChain(kMaxDof),
                                               options(names, "l" + std::to_string(kMaxDof)));
  EXPECT_EQ(at_limit.dof(), kMaxDof);
}

TEST(ModelErrorTest, NonFiniteOptions) {
  ModelOptions bad = options({"shoulder", "elbow"}, "tip");
  bad.gravity_m_per_s2.x() = std::nan("");
  expectModelError([&] { Model::fromUrdfString(test_urdfs::planarTwoLink(), bad); },
                   ModelErrc::kInvalidOption, {"finite"});
}

TEST(ModelErrorTest, ArmatureNeedsOneFiniteNonNegativeEntryPerJoint) {
  ModelOptions bad = options({"shoulder", "elbow"}, "tip");
  bad.armature = {0.1};
  expectModelError([&] { Model::fromUrdfString(test_urdfs::planarTwoLink(), bad); },
                   ModelErrc::kInvalidOption, {"armature has 1 entries for 2 joints"});
  bad.armature = {0.1, -0.2};
  expectModelError([&] { Model::fromUrdfString(test_urdfs::planarTwoLink(), bad); },
                   ModelErrc::kInvalidOption, {"armature of joint 'elbow'", ">= 0"});
  bad.armature = {std::nan(""), 0.2};
  expectModelError([&] { Model::fromUrdfString(test_urdfs::planarTwoLink(), bad); },
                   ModelErrc::kInvalidOption, {"armature of joint 'shoulder'", "finite"});
}

TEST(ModelUpdateTest, NonFiniteOrWrongSizeInputLeavesResultsUntouched) {
  const Model model =
      Model::fromUrdfString(test_urdfs::planarTwoLink(), options({"shoulder", "elbow"}, "tip"));
  Data data(model);
  const std::vector<double> good{0.1, 0.2};
  ASSERT_EQ(update(model, data, good, good, Quantity::kAll), UpdateStatus::kOk);
  const Eigen::Vector3d position = data.tip_position;
  const JointVector gravity = data.gravity;

  const std::vector<double> nan_q{0.5, std::numeric_limits<double>::quiet_NaN()};
  const std::vector<double> inf_dq{0.0, std::numeric_limits<double>::infinity()};
  const std::vector<double> short_q{0.5};
  EXPECT_EQ(update(model, data, nan_q, good, Quantity::kAll), UpdateStatus::kNonFinite);
  EXPECT_EQ(update(model, data, good, inf_dq, Quantity::kAll), UpdateStatus::kNonFinite);
  EXPECT_EQ(update(model, data, short_q, good, Quantity::kAll), UpdateStatus::kSizeMismatch);
  EXPECT_EQ(update(model, data, good, short_q, Quantity::kCoriolis), UpdateStatus::kSizeMismatch);
  EXPECT_EQ(data.tip_position, position);
  EXPECT_EQ(data.gravity, gravity);
  EXPECT_EQ(data.computed, Quantity::kAll);
  // Velocities are not read unless Coriolis is requested.
  EXPECT_EQ(update(model, data, good, inf_dq, Quantity::kGravity), UpdateStatus::kOk);
}

}  // namespace
}  // namespace comply::model
