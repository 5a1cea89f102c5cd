// Where the chain runs in the URDF (chain_path.hpp).

#include "chain_path.hpp"

#include <algorithm>

#include "comply/model/model_error.hpp"

namespace comply::model {

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

}  // namespace comply::model
