// The chain's path through the URDF and its check against the joints asked for (chain_path.hpp).

#include "chain_path.hpp"

#include <algorithm>
#include <string_view>

#include "comply/model/model_error.hpp"

namespace comply::model {
namespace {

std::string joinNames(const std::vector<std::string>& names) {
  std::string joined;
  for (const auto& name : names) {
    joined += (joined.empty() ? "" : ", ") + name;
  }
  return joined;
}

std::string_view jointTypeName(int type) {
  switch (type) {
    case urdf::Joint::REVOLUTE:
      return "revolute";
    case urdf::Joint::CONTINUOUS:
      return "continuous";
    case urdf::Joint::PRISMATIC:
      return "prismatic";
    case urdf::Joint::FLOATING:
      return "floating";
    case urdf::Joint::PLANAR:
      return "planar";
    case urdf::Joint::FIXED:
      return "fixed";
    default:
      return "unknown";
  }
}

}  // namespace

bool isMovable(int type) {
  return type == urdf::Joint::REVOLUTE || type == urdf::Joint::CONTINUOUS ||
         type == urdf::Joint::PRISMATIC;
}

// Every later pass walks between these two links, so both must exist before anything else is read.
ChainEnds findChainEnds(const urdf::ModelInterface& urdf, const ModelOptions& options) {
  const auto root = urdf.getRoot();
  if (!root) {
    throw ModelError(ModelErrc::kInvalidUrdf, "the URDF has no root link");
  }
  const std::string base_name = options.base_frame.empty() ? root->name : options.base_frame;
  const auto base_link = urdf.getLink(base_name);
  if (!base_link) {
    throw ModelError(
        ModelErrc::kUnknownFrame,
        "base frame '" + base_name + "' is not a link of robot '" + urdf.getName() + "'");
  }
  if (options.tip_frame.empty()) {
    throw ModelError(ModelErrc::kUnknownFrame, "no tip frame given");
  }
  const auto tip_link = urdf.getLink(options.tip_frame);
  if (!tip_link) {
    throw ModelError(
        ModelErrc::kUnknownFrame,
        "tip frame '" + options.tip_frame + "' is not a link of robot '" + urdf.getName() + "'");
  }
  if (!options.tcp_offset.matrix().allFinite() || !options.gravity_m_per_s2.allFinite()) {
    throw ModelError(ModelErrc::kInvalidOption, "TCP offset and gravity must be finite");
  }
  return {base_name, tip_link};
}

// A URDF only links children to their parents, so the chain is found by walking up from the tip.
std::vector<urdf::JointConstSharedPtr> baseToTipJoints(const ChainEnds& ends,
                                                       const std::string& tip_frame) {
  std::vector<urdf::JointConstSharedPtr> path;
  for (auto link = ends.tip_link; link->name != ends.base_name; link = link->getParent()) {
    if (!link->parent_joint) {
      throw ModelError(
          ModelErrc::kFrameNotInChain,
          "tip frame '" + tip_frame + "' is not below base frame '" + ends.base_name + "'");
    }
    path.push_back(link->parent_joint);
  }
  std::reverse(path.begin(), path.end());
  return path;
}

// The caller's joint order is kept, so each requested name must name exactly one URDF joint.
std::map<std::string, int> indexRequestedJoints(const urdf::ModelInterface& urdf,
                                                const std::vector<std::string>& joint_names) {
  std::map<std::string, int> user_index;
  std::vector<std::string> unknown;
  std::vector<std::string> duplicate;
  for (int i = 0; i < static_cast<int>(joint_names.size()); ++i) {
    const std::string& name = joint_names[i];
    if (!urdf.getJoint(name)) {
      unknown.push_back(name);
    } else if (!user_index.emplace(name, i).second) {
      duplicate.push_back(name);
    }
  }
  if (!unknown.empty()) {
    throw ModelError(ModelErrc::kUnknownJoint,
                     "robot '" + urdf.getName() + "' has no joint named: " + joinNames(unknown));
  }
  if (!duplicate.empty()) {
    throw ModelError(ModelErrc::kDuplicateJoint,
                     "joints requested more than once: " + joinNames(duplicate));
  }
  return user_index;
}

// Every movable joint on the path is controlled and nothing else is, so no joint is silently
// locked or ignored; returns the number of controlled joints.
std::size_t checkChainMatchesRequest(const std::vector<urdf::JointConstSharedPtr>& path,
                                     const std::map<std::string, int>& user_index,
                                     const ModelOptions& options, const std::string& base_name) {
  std::vector<std::string> missing;
  std::vector<std::string> on_path;
  for (const auto& joint : path) {
    if (joint->type == urdf::Joint::FLOATING || joint->type == urdf::Joint::PLANAR ||
        joint->type == urdf::Joint::UNKNOWN) {
      throw ModelError(ModelErrc::kUnsupportedJoint,
                       "joint '" + joint->name + "' between '" + base_name + "' and '" +
                           options.tip_frame + "' is " + std::string(jointTypeName(joint->type)) +
                           "; only revolute, continuous, prismatic and fixed joints are supported");
    }
    if (isMovable(joint->type)) {
      on_path.push_back(joint->name);
      if (user_index.count(joint->name) == 0) {
        missing.push_back(joint->name);
      }
    }
  }
  std::vector<std::string> off_chain;
  for (const auto& name : options.joint_names) {
    if (std::find(on_path.begin(), on_path.end(), name) == on_path.end()) {
      off_chain.push_back(name);
    }
  }
  if (!off_chain.empty()) {
    throw ModelError(ModelErrc::kJointNotInChain, "joints not movable between '" + base_name +
                                                      "' and '" + options.tip_frame +
                                                      "': " + joinNames(off_chain));
  }
  if (!missing.empty()) {
    throw ModelError(ModelErrc::kMissingJoint,
                     "movable joints between '" + base_name + "' and '" + options.tip_frame +
                         "' not listed as controlled: " + joinNames(missing));
  }
  if (on_path.size() > static_cast<std::size_t>(kMaxDof)) {
    throw ModelError(ModelErrc::kTooManyJoints, "the chain has " + std::to_string(on_path.size()) +
                                                    " movable joints; at most " +
                                                    std::to_string(kMaxDof) + " are supported");
  }
  return on_path.size();
}

}  // namespace comply::model
