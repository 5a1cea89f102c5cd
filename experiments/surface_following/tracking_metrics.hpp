#pragma once
// How well one surface-following run tracked the face: the probe ball's centre against the
// nominal contact path at the commanded arc length, during the traverse, and the contact force
// as a force sensor's filter would report it. Also writes the per-cycle trace the plot reads.

#include <filesystem>
#include <string>

#include "comply/host/sim_session.hpp"
#include "comply/task/path.hpp"
#include "surface_following/surface_following_experiment.hpp"
#include "surface_following/surface_stream.hpp"

namespace comply::experiments::surface_following {

/// The row of `condition` from `log`, a run commanded by `stream` along `tip_path` (where the
/// ball's centre should be); writes every cycle to `trace_file` (CSV).
SurfaceFollowingRow measureTracking(const std::string& condition, const host::SimLog& log,
                                    const SurfaceStream& stream, const task::Path& tip_path,
                                    const std::filesystem::path& trace_file);

}  // namespace comply::experiments::surface_following
