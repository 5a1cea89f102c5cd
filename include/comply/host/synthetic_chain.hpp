#pragma once
// A synthetic serial arm of any DOF for `comply bench`: the cost's growth with the number of
// joints shows on a chain longer than any robot shipped, without adding a robot to robots/.

#include <filesystem>
#include <string>

namespace comply::host {

/// Bench name of the synthetic chain with `dof` joints ("chain12").
std::string syntheticChainName(int dof);

/// The DOF named by `name` when it is a synthetic chain ("chain<N>", 1 <= N <= 12), else 0.
int syntheticChainDof(const std::string& name);

/// Writes robot.yaml and its URDF for a `dof`-joint chain into `folder` (created) and returns it:
/// joints alternate between z and y axes, links shorten and lighten towards the tip, every
/// inertia is physical, and the home pose is away from singularities.
std::filesystem::path writeSyntheticChain(int dof, const std::filesystem::path& folder);

}  // namespace comply::host
