#pragma once
// Where the serial chain a model is built along runs in the URDF: its two ends, and the joints
// between them. Each failure is a ModelError naming the frame.

#include <urdf_model/model.h>

#include <string>
#include <vector>

#include "comply/model/model.hpp"

namespace comply::model {

/// The two ends of the chain, as named by the options and found in the URDF.
struct ChainEnds {
  std::string base_name;
  urdf::LinkConstSharedPtr tip_link;
};

/// Both ends found (and the TCP offset and gravity finite).
ChainEnds findChainEnds(const urdf::ModelInterface& urdf, const ModelOptions& options);

/// Every joint from the base to the tip, fixed ones included, in that order.
std::vector<urdf::JointConstSharedPtr> baseToTipJoints(const ChainEnds& ends,
                                                       const std::string& tip_frame);

}  // namespace comply::model
