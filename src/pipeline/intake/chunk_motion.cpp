// The motion checks of a chunk at the intake (chunk_motion.hpp). The curve is evaluated with the
// player's own code (stages/chunk_track.hpp, stages/chunk_blend.hpp), so what is checked is what
// the cycle will play.

#include "chunk_motion.hpp"

#include <algorithm>
#include <memory>
#include <sstream>
#include <vector>

#include "../stages/chunk_blend.hpp"
#include "../stages/chunk_track.hpp"
#include "comply/core/number_text.hpp"

namespace comply::pipeline {
namespace {

using Eigen::Vector3d;

/// Points per segment of the curve: its velocity is quadratic in time and its acceleration linear
/// (a cubic), so the ends and 15 points between find the peak speed to within 0.1 % and the peak
/// acceleration exactly; the blend's quintic gets as many over its length.
constexpr int kSegmentSamples = 16;
constexpr int kBlendSamples = 32;

Verdict outOfRange(const std::string& message) {
  return {false, RejectionReason::kOutOfRange,
          std::string(toString(RejectionReason::kOutOfRange)) + ": " + message};
}

std::string seconds(double value) {
  std::ostringstream text;
  text << value;
  return text.str();
}

/// "1.45 m/s, above 1 m/s (source)", or "" when `value` is within `limit` (0: no bound).
std::string above(double value, double limit, const char* unit, const char* source) {
  if (!(limit > 0.0) || value <= limit) {
    return {};
  }
  const NumberTexts texts = numbersApart(value, limit);
  return texts.value + " " + unit + ", above " + texts.limit + " " + unit + " (" + source + ")";
}

// ---- the limits, per kind
// ------------------------------------------------------------------------

std::string tooFast(const Vector3d& linear, const Vector3d& angular, const ChunkLimits& arm) {
  std::string why =
      above(linear.norm(), arm.tcp_speed_m_per_s, "m/s", "governor.tcp_speed_m_per_s");
  if (why.empty()) {
    why = above(angular.norm(), arm.tcp_angular_speed_rad_per_s, "rad/s",
                "governor.tcp_angular_speed_rad_per_s");
  }
  return why;
}

std::string tooFast(const JointVector& velocity, const ChunkLimits& arm) {
  const Eigen::Index count = std::min(velocity.size(), arm.joint_speed.size());
  for (Eigen::Index i = 0; i < count; ++i) {
    std::string why = above(std::abs(velocity[i]), arm.joint_speed[i], "rad/s",
                            "governor.velocity_fraction of its URDF velocity limit");
    if (!why.empty()) {
      return "joint " + std::to_string(i + 1) + " at " + why;
    }
  }
  return {};
}

std::string tooQuick(const chunk::CartesianMotion& m, const ValidationConfig& limits) {
  std::string why = above(m.acceleration.norm(), limits.max_chunk_acceleration_m_per_s2, "m/s^2",
                          "validation.max_chunk_acceleration_m_per_s2");
  if (why.empty()) {
    why = above(m.angular_acceleration.norm(), limits.max_chunk_angular_acceleration_rad_per_s2,
                "rad/s^2", "validation.max_chunk_angular_acceleration_rad_per_s2");
  }
  return why;
}

std::string tooQuick(const chunk::JointMotion& m, const ValidationConfig& limits) {
  for (Eigen::Index i = 0; i < m.acceleration.size(); ++i) {
    std::string why =
        above(std::abs(m.acceleration[i]), limits.max_chunk_joint_acceleration_rad_per_s2,
              "rad/s^2", "validation.max_chunk_joint_acceleration_rad_per_s2");
    if (!why.empty()) {
      return "joint " + std::to_string(i + 1) + " at " + why;
    }
  }
  return {};
}

std::string tooFast(const chunk::CartesianMotion& m, const ChunkLimits& arm) {
  return tooFast(m.velocity, m.angular_velocity, arm);
}
std::string tooFast(const chunk::JointMotion& m, const ChunkLimits& arm) {
  return tooFast(m.velocity, arm);
}

/// value / limit, 0 without a bound: how far past its limit a sample is, to find a segment's peak.
double ratio(double value, double limit) {
  return limit > 0.0 ? value / limit : 0.0;
}

double speedRatio(const chunk::CartesianMotion& m, const ChunkLimits& arm) {
  return std::max(ratio(m.velocity.norm(), arm.tcp_speed_m_per_s),
                  ratio(m.angular_velocity.norm(), arm.tcp_angular_speed_rad_per_s));
}
double speedRatio(const chunk::JointMotion& m, const ChunkLimits& arm) {
  double worst = 0.0;
  for (Eigen::Index i = 0; i < std::min(m.velocity.size(), arm.joint_speed.size()); ++i) {
    worst = std::max(worst, ratio(std::abs(m.velocity[i]), arm.joint_speed[i]));
  }
  return worst;
}
double accelerationRatio(const chunk::CartesianMotion& m, const ValidationConfig& limits) {
  return std::max(
      ratio(m.acceleration.norm(), limits.max_chunk_acceleration_m_per_s2),
      ratio(m.angular_acceleration.norm(), limits.max_chunk_angular_acceleration_rad_per_s2));
}
double accelerationRatio(const chunk::JointMotion& m, const ValidationConfig& limits) {
  return ratio(m.acceleration.cwiseAbs().maxCoeff(),
               limits.max_chunk_joint_acceleration_rad_per_s2);
}

/// A waypoint's given velocity (its twist, its joint velocity).
std::string givenTooFast(const CartesianCommand& command, const ChunkLimits& arm) {
  return tooFast(command.twist.head<3>(), command.twist.tail<3>(), arm);
}
std::string givenTooFast(const JointCommand& command, const ChunkLimits& arm) {
  return tooFast(command.velocity, arm);
}

/// The chord from pose `from` to `to` in `dt_s`.
std::string chordTooFast(const Vector3d& from_position, const Eigen::Quaterniond& from_orientation,
                         const CartesianCommand& to, double dt_s, const ChunkLimits& arm) {
  const double angle = from_orientation.angularDistance(to.orientation);
  return tooFast((to.position - from_position) / dt_s, Vector3d(angle / dt_s, 0.0, 0.0), arm);
}
std::string chordTooFast(const CartesianCommand& from, const CartesianCommand& to, double dt_s,
                         const ChunkLimits& arm) {
  return chordTooFast(from.position, from.orientation, to, dt_s, arm);
}
std::string chordTooFast(const JointCommand& from, const JointCommand& to, double dt_s,
                         const ChunkLimits& arm) {
  return tooFast((to.position - from.position) / dt_s, arm);
}
std::string measuredTooFast(const MeasuredPose& measured, const CartesianCommand& to, double dt_s,
                            const ChunkLimits& arm) {
  return chordTooFast(measured.tcp_position, measured.tcp_orientation, to, dt_s, arm);
}
std::string measuredTooFast(const MeasuredPose& measured, const JointCommand& to, double dt_s,
                            const ChunkLimits& arm) {
  if (measured.position.size() != to.position.size()) {
    return {};
  }
  return tooFast((to.position - measured.position) / dt_s, arm);
}

// ---- the curve
// -----------------------------------------------------------------------------------

/// Where on the curve `place` is, in the chunk's numbering (the track's 0 is the lead-in).
std::string whereOn(const chunk::Place& place, int track_count) {
  if (place.length_s == 0.0) {
    return place.index == 0 ? "before waypoint 0, held at its lead-in"
                            : "after its last waypoint, " + std::to_string(track_count - 2);
  }
  if (place.index == 0) {
    return "into waypoint 0 (its lead-in from rest)";
  }
  return "from waypoint " + std::to_string(place.index - 1) + " to " + std::to_string(place.index);
}

struct Sample {
  double t_s;
  chunk::Place place;
};

/// The times the curve is checked at, in order: each segment still to play at kSegmentSamples + 1
/// points, its ends included, and the blend's length after `host_time_s`.
template <typename Bus>
std::vector<Sample> samplesOf(const chunk::Track<Bus>& track, double host_time_s, double blend_s) {
  std::vector<Sample> samples;
  int cursor = 0;
  samples.push_back({host_time_s, chunk::placeOf(track, host_time_s, cursor)});
  for (int j = 0; j + 1 < track.count; ++j) {
    const double length = track.time_s[j + 1] - track.time_s[j];
    for (int i = 0; i <= kSegmentSamples && track.time_s[j + 1] > host_time_s; ++i) {
      const double fraction = static_cast<double>(i) / kSegmentSamples;
      const double t = track.time_s[j] + fraction * length;
      if (t >= host_time_s) {
        samples.push_back({t, {j, fraction, length}});
      }
    }
  }
  for (int i = 1; i <= kBlendSamples && blend_s > 0.0; ++i) {
    const double t = host_time_s + blend_s * static_cast<double>(i) / kBlendSamples;
    cursor = 0;
    samples.push_back({t, chunk::placeOf(track, t, cursor)});
  }
  std::stable_sort(samples.begin(), samples.end(),
                   [](const Sample& a, const Sample& b) { return a.t_s < b.t_s; });
  return samples;
}

/// The reference the cycle will write at each sample: the curve, and the blend over its length.
template <typename Bus>
class Reference {
 public:
  Reference(const chunk::Track<Bus>& track, const Bus* in_force, double blend_s, double host_time_s)
      : track_(track), blend_s_(in_force != nullptr ? blend_s : 0.0), host_time_s_(host_time_s) {
    if (blend_s_ > 0.0) {
      int cursor = 0;
      offset_ = chunk::offsetAt(*in_force,
                                chunk::motionAt(track, chunk::placeOf(track, host_time_s, cursor)));
    }
  }
  [[nodiscard]] auto at(const Sample& sample) const {
    auto motion = chunk::motionAt(track_, sample.place);
    chunk::blendInto(offset_, blend_s_, sample.t_s - host_time_s_, motion);
    return motion;
  }
  [[nodiscard]] bool blending(const Sample& sample) const {
    return blend_s_ > 0.0 && sample.t_s - host_time_s_ < blend_s_;
  }
  [[nodiscard]] double blendS() const { return blend_s_; }

 private:
  const chunk::Track<Bus>& track_;
  double blend_s_;
  double host_time_s_;
  chunk::OffsetOf<Bus> offset_{};
};

/// The first sample past a limit, then the peak of its segment on that limit: why, or "".
template <typename Bus>
std::string firstExcess(const std::vector<Sample>& samples, const Reference<Bus>& reference,
                        int last_segment, const ValidationConfig& limits, const ChunkLimits& arm,
                        std::size_t& at) {
  for (std::size_t i = 0; i < samples.size(); ++i) {
    const auto motion = reference.at(samples[i]);
    // The last segment brings a chunk that runs out to rest on its last waypoint (4 v / h at its
    // end): a chunk is normally replaced before, and a policy's 0.2 m/s with waypoints 20 ms
    // apart would need 40 m/s^2 there. Held to the speeds alone, unless the blend acts in it.
    const bool stopping = samples[i].place.index == last_segment && !reference.blending(samples[i]);
    const bool fast = !tooFast(motion, arm).empty();
    if (!fast && (stopping || tooQuick(motion, limits).empty())) {
      continue;
    }
    const auto measure = [&](const Sample& sample) {
      const auto m = reference.at(sample);
      return fast ? speedRatio(m, arm) : accelerationRatio(m, limits);
    };
    at = i;
    for (std::size_t k = i + 1;
         k < samples.size() && samples[k].place.index == samples[i].place.index; ++k) {
      if (measure(samples[k]) > measure(samples[at])) {
        at = k;
      }
    }
    const auto peak = reference.at(samples[at]);
    return fast ? tooFast(peak, arm) : tooQuick(peak, limits);
  }
  return {};
}

template <typename Command>
Verdict checkCurve(const Chunk<Command>& chunk, int dof, const ValidationConfig& limits,
                   const ChunkLimits& arm, double host_time_s, const CommandBus* in_force,
                   bool waits) {
  using Bus = BusOf<Command>;
  const auto track = std::make_unique<chunk::Track<Bus>>();  // large: not on the stack
  const int n = static_cast<int>(chunk.waypoints.size());
  track->count = n + 1;
  track->fields = static_cast<std::uint32_t>(chunk.fields);
  track->stamp_s = chunk.stamp_s;
  track->takeover_s = chunk.takeover_s;
  for (int k = 0; k < n; ++k) {
    track->time_s[k + 1] = chunk.waypoints[k].time_s;
    track->waypoints[k + 1] = schema::toBus(chunk.waypoints[k].command, dof);
  }
  const Bus* from = in_force != nullptr ? std::get_if<Bus>(in_force) : nullptr;
  chunk::derive(*track, waits ? from : nullptr);  // as the player will (ChunkPlayer::load)
  const Reference<Bus> reference(*track, from, arm.blend_time_s, host_time_s);
  const std::vector<Sample> samples = samplesOf(*track, host_time_s, reference.blendS());
  std::size_t at = 0;
  const std::string why = firstExcess(samples, reference, track->count - 2, limits, arm, at);
  if (why.empty()) {
    return {};
  }
  const Sample& peak = samples[at];
  return outOfRange("the curve " + whereOn(peak.place, track->count) + " reaches " + why + ", " +
                    seconds(peak.t_s - host_time_s) + " s from now" +
                    (reference.blending(peak) ? " with the blend from the reference in force "
                                                "(chunk_blend_time_s " +
                                                    seconds(reference.blendS()) + " s)"
                                              : std::string()));
}

template <typename Command>
Verdict checkAny(const Chunk<Command>& chunk, int dof, const ValidationConfig& limits,
                 const ChunkLimits& arm, const MeasuredPose& measured, double host_time_s,
                 const CommandBus* in_force, bool waits) {
  const auto& w = chunk.waypoints;
  const int n = static_cast<int>(w.size());
  int ahead = 0;  // the first waypoint not yet past (there is one: the chunk is not late)
  while (ahead + 1 < n && !(w[ahead].time_s > host_time_s)) {
    ++ahead;
  }
  const int first = std::max(0, ahead - 1);  // the first waypoint of a segment still to play
  for (int k = first; k < n && has(chunk.fields, CommandField::kVelocity); ++k) {
    if (const std::string why = givenTooFast(w[k].command, arm); !why.empty()) {
      return outOfRange("waypoint " + std::to_string(k) + "'s velocity: " + why);
    }
  }
  for (int k = first; k + 1 < n; ++k) {
    const double dt_s = w[k + 1].time_s - w[k].time_s;
    if (const std::string why = chordTooFast(w[k].command, w[k + 1].command, dt_s, arm);
        !why.empty()) {
      return outOfRange("waypoint " + std::to_string(k) + " to " + std::to_string(k + 1) + " in " +
                        seconds(dt_s) + " s: " + why);
    }
  }
  if (measured.valid) {
    // The reference takes at least the blend to reach the chunk from where it is.
    const double dt_s = std::max(w[ahead].time_s - host_time_s, arm.blend_time_s);
    if (const std::string why = measuredTooFast(measured, w[ahead].command, dt_s, arm);
        dt_s > 0.0 && !why.empty()) {
      return outOfRange("the measured pose to waypoint " + std::to_string(ahead) + " in " +
                        seconds(dt_s) + " s: " + why);
    }
  }
  return checkCurve(chunk, dof, limits, arm, host_time_s, in_force, waits);
}

}  // namespace

Verdict checkChunkMotion(const CartesianChunk& chunk, int dof, const ValidationConfig& limits,
                         const ChunkLimits& arm, const MeasuredPose& measured, double host_time_s,
                         const CommandBus* in_force, bool waits) {
  return checkAny(chunk, dof, limits, arm, measured, host_time_s, in_force, waits);
}

Verdict checkChunkMotion(const JointChunk& chunk, int dof, const ValidationConfig& limits,
                         const ChunkLimits& arm, const MeasuredPose& measured, double host_time_s,
                         const CommandBus* in_force, bool waits) {
  return checkAny(chunk, dof, limits, arm, measured, host_time_s, in_force, waits);
}

}  // namespace comply::pipeline
