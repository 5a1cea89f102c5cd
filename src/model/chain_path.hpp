#pragma once
// The serial chain a model is built along: its two ends in the URDF, the joints between them, and
// the check that the joints asked for are exactly the movable ones on that path. Each failure is
// a ModelError naming the frame or joint.

#include <urdf_model/model.h>

#include <cstddef>
#include <map>
#include <string>
#include <vector>

#include "comply/model/model.hpp"

namespace comply::model {

/// The two ends of the chain, as named by the options and found in the URDF.
struct ChainEnds {
  std::string base_name;
  urdf::LinkConstSharedPtr tip_link;
};

/// Revolute, continuous or prismatic: a joint the model controls.
bool isMovable(int type);

/// Both ends found (and the TCP offset and gravity finite).
ChainEnds findChainEnds(const urdf::ModelInterface& urdf, const ModelOptions& options);

/// Every joint from the base to the tip, fixed ones included, in that order.
std::vector<urdf::JointConstSharedPtr> baseToTipJoints(const ChainEnds& ends,
                                                       const std::string& tip_frame);

/// Each requested joint's name to its place in the request.
std::map<std::string, int> indexRequestedJoints(const urdf::ModelInterface& urdf,
                                                const std::vector<std::string>& joint_names);

/// The number of controlled joints, once the path's movable joints are the requested ones.
std::size_t checkChainMatchesRequest(const std::vector<urdf::JointConstSharedPtr>& path,
                                     const std::map<std::string, int>& user_index,
                                     const ModelOptions& options, const std::string& base_name);

}  // namespace comply::model
