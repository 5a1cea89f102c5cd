#pragma once
// Errors raised while building a model. Loading happens outside the real-time path, so it reports
// through exceptions that carry a machine-readable code and a message naming the culprit.

#include <stdexcept>
#include <string>
#include <string_view>

namespace comply::model {

enum class ModelErrc {
  kFileNotFound,       ///< URDF or robot folder does not exist
  kInvalidUrdf,        ///< urdfdom could not parse the description
  kInvalidDescription, ///< robot.yaml is malformed or inconsistent
  kUnknownRobot,       ///< no robot of that name under the robot search path
  kUnknownJoint,       ///< a requested joint name is not in the URDF
  kMissingJoint,       ///< a movable joint of the chain was not listed as controlled
  kDuplicateJoint,     ///< a joint name was requested twice
  kJointNotInChain,    ///< a requested joint exists but is not between base and tip
  kUnknownFrame,       ///< base or tip frame is not a link of the URDF
  kFrameNotInChain,    ///< the tip frame is not a descendant of the base frame
  kUnsupportedJoint,   ///< floating or planar joint between base and tip
  kTooManyJoints,      ///< more controlled joints than kMaxDof
  kInvalidInertia,     ///< negative mass or non-finite inertial parameters
  kInvalidOption,      ///< a non-finite TCP offset or gravity vector
};

/// Name of an error code as it appears in messages ("unknown_joint", ...).
std::string_view toString(ModelErrc code);

class ModelError : public std::runtime_error {
 public:
  ModelError(ModelErrc code, const std::string& message);
  [[nodiscard]] ModelErrc code() const noexcept { return code_; }
  /// The message without the code prefix, for wrapping with more context.
  [[nodiscard]] const std::string& detail() const noexcept { return detail_; }

 private:
  ModelErrc code_;
  std::string detail_;
};

}  // namespace comply::model
