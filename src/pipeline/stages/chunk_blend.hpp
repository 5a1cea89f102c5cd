#pragma once
// The blend that takes a new chunk over from the reference in force (chunk_player.hpp): the
// difference between the two when the chunk starts, in value and velocity, decays along a quintic
// to zero. The acceleration is left to step, as it does at every waypoint of a chunk's C1 curve:
// decaying it too would overshoot the chunk's own acceleration (the quintic's curvature term
// swings past zero), so a chunk that continues the committed curve in position and velocity would
// play rougher than its own curve instead of exactly on it. The player adds it every cycle of the
// blend; the intake evaluates the same sum to check what the blend asks of the arm
// (chunk_motion.cpp). Real-time safe.

#include <algorithm>
#include <type_traits>

#include "chunk_curve.hpp"
#include "chunk_track.hpp"
#include "comply/core/rotation.hpp"

namespace comply::pipeline::chunk {

/// The difference between the reference in force and the chunk when the chunk starts, in value
/// and velocity, which the blend lets decay to zero.
struct CartesianOffset {
  Vector3d position[2];
  Vector3d rotation[2];  ///< rotation vector (base frame) from the chunk's orientation to the old
};
struct JointOffset {
  JointVector position[2];
};

inline CartesianOffset offsetAt(const Cartesian& from, const CartesianMotion& chunk) noexcept {
  CartesianOffset offset;
  offset.position[0] = ConstVector3Map(from.position) - chunk.position;
  offset.position[1] = ConstVector3Map(from.twist) - chunk.velocity;
  // orientationError(a, b) is the base-frame rotation vector taking a to b.
  offset.rotation[0] = orientationError(chunk.orientation, fromXyzw(from.orientation));
  offset.rotation[1] = ConstVector3Map(from.twist + 3) - chunk.angular_velocity;
  return offset;
}

inline JointOffset offsetAt(const Joint& from, const JointMotion& chunk) noexcept {
  const int dof = from.dof;
  JointOffset offset;
  offset.position[0] = Eigen::Map<const Eigen::VectorXd>(from.position, dof) - chunk.position;
  offset.position[1] = Eigen::Map<const Eigen::VectorXd>(from.velocity, dof) - chunk.velocity;
  return offset;
}

/// value, d/dt, d^2/dt^2 of a decaying offset `e` (value, velocity) at blend fraction s of a
/// blend of `length_s`.
template <typename Value>
inline void decay(const Value (&e)[2], const curve::QuinticWeights& w, double length_s,
                  Value (&out)[3]) {
  const double t = length_s;
  out[0] = w.value[0] * e[0] + t * w.value[1] * e[1];
  out[1] = (w.first[0] * e[0] + t * w.first[1] * e[1]) / t;
  out[2] = (w.second[0] * e[0] + t * w.second[1] * e[1]) / (t * t);
}

inline void addOffset(const CartesianOffset& e, const curve::QuinticWeights& w, double length_s,
                      CartesianMotion& m) noexcept {
  Vector3d position[3];
  Vector3d rotation[3];
  decay(e.position, w, length_s, position);
  decay(e.rotation, w, length_s, rotation);
  m.position += position[0];
  m.velocity += position[1];
  m.acceleration += position[2];
  // The rotation's rates add as vectors, which holds to first order in the offset's angle (the
  // exact rate of Exp(e) q has Jacobian terms in e): the offset is small when a chunk continues
  // the one before it, and the orientation itself stays continuous whatever its size.
  m.orientation = (quaternionExp(rotation[0]) * m.orientation).normalized();
  m.angular_velocity += rotation[1];
  m.angular_acceleration += rotation[2];
}

inline void addOffset(const JointOffset& e, const curve::QuinticWeights& w, double length_s,
                      JointMotion& m) noexcept {
  JointVector position[3];
  decay(e.position, w, length_s, position);
  m.position += position[0];
  m.velocity += position[1];
  m.acceleration += position[2];
}

/// Adds the blend at `since_start_s` after the chunk started (offset `e`, blend of `length_s`) to
/// the chunk's `motion`; returns how far the settings have faded in (1 once the blend is over).
template <typename Offset, typename Motion>
inline double blendInto(const Offset& e, double length_s, double since_start_s,
                        Motion& motion) noexcept {
  if (!(length_s > 0.0) || since_start_s >= length_s) {
    return 1.0;
  }
  const curve::QuinticWeights w = curve::quinticDecay(std::max(0.0, since_start_s) / length_s);
  addOffset(e, w, length_s, motion);
  return 1.0 - w.value[0];
}

template <typename Bus>
using OffsetOf = std::conditional_t<std::is_same_v<Bus, Cartesian>, CartesianOffset, JointOffset>;

}  // namespace comply::pipeline::chunk
