#pragma once
// One loaded chunk (chunk_player.hpp has the rules): its waypoints on the controller's clock after
// the lead-in, the velocities and orientation segments derived when the intake loads it, and its
// curve and settings evaluated at a time. Private to the pipeline: chunk_player.cpp plays it.

#include <Eigen/Geometry>
#include <algorithm>
#include <array>
#include <cstdint>

#include "comply/core/capacity.hpp"
#include "comply/core/chunk.hpp"
#include "comply/plugin/abi.h"
#include "comply/schema/schema.hpp"

namespace comply::pipeline::chunk {

using Cartesian = comply_cartesian_command;
using Joint = comply_joint_command;
using Eigen::Vector3d;
using Vector3Map = Eigen::Map<Vector3d>;
using ConstVector3Map = Eigen::Map<const Vector3d>;

using schema::fromXyzw;
using schema::toXyzw;

/// to = a + (b - a) * fraction, entry by entry.
inline void lerp(const double* a, const double* b, double fraction, int size, double* to) noexcept {
  for (int i = 0; i < size; ++i) {
    to[i] = a[i] + (b[i] - a[i]) * fraction;
  }
}

inline Eigen::Quaterniond slerpShort(const Eigen::Quaterniond& a, const Eigen::Quaterniond& b,
                                     double fraction) noexcept {
  return a.slerp(fraction, b).normalized();  // Eigen's slerp takes the short way
}

/// The orientation part of one segment, precomputed at load: the rotation vector from its first
/// waypoint to its second (in the first's frame) and the Hermite end slopes of that vector over
/// the segment [rad], so the cycle evaluates it without a logarithm or an inverse.
struct RotationSegment {
  Vector3d phi = Vector3d::Zero();
  Vector3d slope0 = Vector3d::Zero();
  Vector3d slope1 = Vector3d::Zero();
};

/// A loaded chunk: its waypoints after a lead-in waypoint (index 0) that the intake adds one
/// segment before the first, half that segment's travel behind it at the first's velocity, and at
/// rest: from there the reference accelerates evenly into the first waypoint, so the curve is C1
/// also where a chunk that starts in the future begins.
inline constexpr int kTrackWaypoints = kMaxChunkWaypoints + 1;

template <typename Bus>
struct Track {
  int count = 0;  ///< the chunk's waypoints plus the lead-in
  std::uint32_t fields = 0;
  double stamp_s = 0.0;
  std::uint64_t sequence = 0;  ///< its number (CommandId), 0: not known
  // On the controller's clock [s], NaN when not given (chunk_timing.hpp).
  double observation_s = 0.0;
  double received_s = 0.0;
  double takeover_s = 0.0;  ///< NaN: at once
  std::array<double, kTrackWaypoints> time_s{};
  /// Each waypoint's bus; its twist (velocity) holds the waypoint's velocity, given or implied.
  std::array<Bus, kTrackWaypoints> waypoints{};
  std::array<RotationSegment, kTrackWaypoints> rotation{};  // Cartesian only
};

/// Where the reference is at one time: value, velocity, acceleration.
struct CartesianMotion {
  Vector3d position = Vector3d::Zero();
  Vector3d velocity = Vector3d::Zero();
  Vector3d acceleration = Vector3d::Zero();
  Eigen::Quaterniond orientation = Eigen::Quaterniond::Identity();
  Vector3d angular_velocity = Vector3d::Zero();
  Vector3d angular_acceleration = Vector3d::Zero();
};
struct JointMotion {
  JointVector position, velocity, acceleration;
};

/// Where `t_s` falls: waypoint `index` and the fraction of the segment after it; before the first
/// waypoint and after the last the chunk holds that end (length 0).
struct Place {
  int index = 0;
  double fraction = 0.0;
  double length_s = 0.0;  ///< the segment's length, 0 when holding an end
};

/// Where `t_s` falls on `track`; `cursor` is the segment found the last time, where the search
/// starts (a chunk's time only moves forward), and is moved to this one.
template <typename Bus>
Place placeOf(const Track<Bus>& track, double t_s, int& cursor) noexcept {
  const int last = track.count - 1;
  if (last == 0 || t_s < track.time_s[0]) {
    return {0, 0.0, 0.0};
  }
  if (t_s >= track.time_s[last]) {
    return {last, 0.0, 0.0};
  }
  cursor = std::clamp(cursor, 0, last - 1);
  while (cursor > 0 && track.time_s[cursor] > t_s) {
    --cursor;
  }
  while (cursor + 1 < last && track.time_s[cursor + 1] <= t_s) {
    ++cursor;
  }
  const double length = track.time_s[cursor + 1] - track.time_s[cursor];
  return {cursor, (t_s - track.time_s[cursor]) / length, length};
}

/// Fills the waypoints' velocities (unless the chunk gives them), the lead-in (index 0) and, for
/// Cartesian chunks, the orientation segments; the intake calls it after writing waypoints
/// 1..count-1. `joins`: the reference in force at the track's takeover time, for a chunk that
/// waits for it; the waypoint at that time (but the last) then takes the reference's velocity
/// instead of the implied one, so the chunk leaves the curve in force there without a kink: a
/// policy's chunk that keeps the committed prefix up to that waypoint continues it in position
/// and velocity, and its blend has nothing to take away. Allocates (non-real-time).
void derive(Track<Cartesian>& track, const Cartesian* joins = nullptr);
void derive(Track<Joint>& track, const Joint* joins = nullptr);

/// The curve at a place (placeOf).
CartesianMotion motionAt(const Track<Cartesian>& track, const Place& place) noexcept;
JointMotion motionAt(const Track<Joint>& track, const Place& place) noexcept;

/// The chunk's gains, feedforward, task frame and nullspace at a place, written into `to`:
/// linear between the segment's waypoints, the task frame by spherical interpolation.
void settingsAt(const Track<Cartesian>& track, const Place& place, Cartesian& to) noexcept;
void settingsAt(const Track<Joint>& track, const Place& place, Joint& to) noexcept;

}  // namespace comply::pipeline::chunk
