#pragma once
// urdfdom -> KDL::Chain conversion for the test oracles and the side-by-side benchmark. Written
// here (not kdl_parser, not our model code) so a URDF-handling mistake cannot hide in both.

#include <kdl/chain.hpp>
#include <string>
#include <vector>

namespace comply::testing {

struct KdlUrdfChain {
  KDL::Chain chain;
  /// Movable joints of the chain in chain order (base to tip).
  std::vector<std::string> movable_joint_names;
};

/// Reads `urdf_path` and extracts the chain base_link -> tip_link. Throws std::runtime_error on an
/// unreadable URDF, a joint type KDL cannot represent, a mimic joint or a missing link.
KdlUrdfChain kdlChainFromUrdf(const std::string& urdf_path, const std::string& base_link,
                              const std::string& tip_link);

}  // namespace comply::testing
