#include "comply/model/model_error.hpp"

namespace comply::model {

std::string_view toString(ModelErrc code) {
  switch (code) {
    case ModelErrc::kFileNotFound:
      return "file_not_found";
    case ModelErrc::kInvalidUrdf:
      return "invalid_urdf";
    case ModelErrc::kInvalidDescription:
      return "invalid_description";
    case ModelErrc::kUnknownRobot:
      return "unknown_robot";
    case ModelErrc::kUnknownJoint:
      return "unknown_joint";
    case ModelErrc::kMissingJoint:
      return "missing_joint";
    case ModelErrc::kDuplicateJoint:
      return "duplicate_joint";
    case ModelErrc::kJointNotInChain:
      return "joint_not_in_chain";
    case ModelErrc::kUnknownFrame:
      return "unknown_frame";
    case ModelErrc::kFrameNotInChain:
      return "frame_not_in_chain";
    case ModelErrc::kUnsupportedJoint:
      return "unsupported_joint";
    case ModelErrc::kTooManyJoints:
      return "too_many_joints";
    case ModelErrc::kInvalidInertia:
      return "invalid_inertia";
    case ModelErrc::kInvalidOption:
      return "invalid_option";
  }
  return "unknown_error";
}

ModelError::ModelError(ModelErrc code, const std::string& message)
    : std::runtime_error(std::string(toString(code)) + ": " + message),
      code_(code),
      detail_(message) {}

}  // namespace comply::model
