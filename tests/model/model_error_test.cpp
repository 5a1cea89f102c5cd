// Every way a model can be asked for wrongly gives a named error, never a crash.

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <limits>

#include "comply/model/model_error.hpp"
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
      EXPECT_NE(message.find(fragment), std::string::npos) << "'" << fragment << "' not in: "
                                                           << message;
    }
  }
}

TEST(ModelErrorTest, MissingFile) {
  expectModelError(
      [] { Model::fromUrdfFile("/nonexistent/robot.urdf", options({"a"}, "tip")); },
      ModelErrc::kFileNotFound, {"/nonexistent/robot.urdf"});
}

TEST(ModelErrorTest, InvalidXml) {
  expectModelError([] { Model::fromUrdfString("<robot name='x'><link", options({"a"}, "t")); },
                   ModelErrc::kInvalidUrdf, {});
  const auto path = std::filesystem::temp_directory_path() / "comply_invalid.urdf";
  std::ofstream(path) << "not xml at all";
  expectModelError([&] { Model::fromUrdfFile(path, options({"a"}, "t")); },
                   ModelErrc::kInvalidUrdf, {path.string()});
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
