#include "comply/model/model_error.hpp"

#include "comply/core/enum_names.hpp"

namespace comply::model {
namespace {

constexpr EnumNames<ModelErrc, 14> kModelErrcNames{
    {{ModelErrc::kFileNotFound, "file_not_found"},
     {ModelErrc::kInvalidUrdf, "invalid_urdf"},
     {ModelErrc::kInvalidDescription, "invalid_description"},
     {ModelErrc::kUnknownRobot, "unknown_robot"},
     {ModelErrc::kUnknownJoint, "unknown_joint"},
     {ModelErrc::kMissingJoint, "missing_joint"},
     {ModelErrc::kDuplicateJoint, "duplicate_joint"},
     {ModelErrc::kJointNotInChain, "joint_not_in_chain"},
     {ModelErrc::kUnknownFrame, "unknown_frame"},
     {ModelErrc::kFrameNotInChain, "frame_not_in_chain"},
     {ModelErrc::kUnsupportedJoint, "unsupported_joint"},
     {ModelErrc::kTooManyJoints, "too_many_joints"},
     {ModelErrc::kInvalidInertia, "invalid_inertia"},
     {ModelErrc::kInvalidOption, "invalid_option"}}};

}  // namespace

std::string_view toString(ModelErrc code) {
  return nameIn(kModelErrcNames, code, "unknown_error");
}

ModelError::ModelError(ModelErrc code, const std::string& message)
    : std::runtime_error(std::string(toString(code)) + ": " + message),
      code_(code),
      detail_(message) {}

}  // namespace comply::model
