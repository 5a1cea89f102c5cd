#pragma once
// One run of the chunk experiment (chunk_experiment.hpp): the FR3 under the Cartesian impedance
// plugin tracks a circle that a scripted "policy" commands, either as stepped setpoints (one
// target per policy step, held until the next, as DROID's controller took them) or as timed
// chunks (pipeline/chunk_player.hpp). The policy acts on an observation and its action reaches
// the host `latency_s` later; each action carries an error of its own (a learned policy's
// consecutive outputs disagree), so a new chunk must take over from the old one.

#include <cstdint>
#include <filesystem>
#include <string>

namespace comply::experiments::chunks {

enum class Mode { kStepped, kChunks };

struct Condition {
  std::string name;  ///< "stepped_15hz", "chunks_10hz", ...
  Mode mode = Mode::kChunks;
  double rate_hz = 10.0;  ///< how often the policy acts
};

struct RunSettings {
  double duration_s = 6.0;
  double circle_radius_m = 0.05;
  double circle_period_s = 2.0;   ///< 0.157 m/s along the circle
  double start_s = 0.5;           ///< the policy starts acting here (the arm at rest before)
  double settle_s = 1.5;          ///< the metrics start here
  double step_s = 1.0 / 15.0;     ///< spacing of a chunk's waypoints (DROID's action period)
  int chunk_steps = 16;           ///< waypoints per chunk
  double latency_s = 0.04;        ///< from the observation to the action at the host
  double action_error_m = 0.001;  ///< standard deviation of each action's error, per axis
  std::uint32_t seed = 1;
};

struct RunResult {
  double rmse_mm = 0.0;  ///< TCP against the circle, after settle_s
  double max_error_mm = 0.0;
  double max_torque_rate_nm_per_s = 0.0;    ///< any joint, any cycle after start_s
  std::uint64_t rate_limit_hits = 0;        ///< joint-cycles clipped by the torque-rate limit
  double max_reference_jerk = 0.0;          ///< m/s^3, third difference of the reference position
  double max_reference_acceleration = 0.0;  ///< m/s^2, second difference
  /// m/s: the largest change of the reference's finite-difference velocity in one cycle.
  double max_reference_velocity_step = 0.0;
  std::uint64_t actions = 0;
  std::uint64_t rejections = 0;
  std::uint64_t faults = 0;
};

/// Runs `condition`; writes every cycle to `trace_file` (CSV). Throws when the controller refuses
/// an action (the experiment's actions are all valid).
RunResult runCondition(const Condition& condition, const RunSettings& settings,
                       const std::filesystem::path& trace_file);

}  // namespace comply::experiments::chunks
