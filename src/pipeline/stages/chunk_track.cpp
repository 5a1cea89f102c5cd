#include "chunk_track.hpp"

#include <algorithm>
#include <cmath>

#include "chunk_curve.hpp"
#include "comply/core/rotation.hpp"

namespace comply::pipeline::chunk {
namespace {

// ---- derived at load (intake thread) ----------------------------------------------------------

/// Implied velocity at waypoints first..count-1 of values `at(k)` (a vector type): the
/// interval-weighted mean of the neighbouring secants inside, the secant at the first, zero at the
/// last (a chunk comes to rest at its end).
template <typename Value, typename At>
void impliedVelocities(const std::array<double, kTrackWaypoints>& time_s, int first, int count,
                       At&& at, Value* velocity) {
  for (int k = first; k < count; ++k) {
    if (k == count - 1) {
      velocity[k] = at(k) * 0.0;
    } else if (k == first) {
      velocity[k] = (at(k + 1) - at(k)) / (time_s[k + 1] - time_s[k]);
    } else {
      const double before = time_s[k] - time_s[k - 1];
      const double after = time_s[k + 1] - time_s[k];
      const Value secant_before = (at(k) - at(k - 1)) / before;
      const Value secant_after = (at(k + 1) - at(k)) / after;
      velocity[k] = (after * secant_before + before * secant_after) / (before + after);
    }
  }
}

/// The waypoint at the track's takeover time, but the last (a chunk ends at rest); -1: none.
template <typename Bus>
int joiningWaypoint(const Track<Bus>& track) {
  constexpr double kSameTime_s = 1e-9;  // the takeover is a waypoint's time, as the sender gave it
  for (int k = 1; k + 1 < track.count; ++k) {
    if (std::abs(track.time_s[k] - track.takeover_s) <= kSameTime_s) {
      return k;
    }
  }
  return -1;
}

/// The lead-in's time: one segment before the first waypoint (1 s for a chunk of one).
template <typename Bus>
double leadInTime(const Track<Bus>& track) {
  const double segment_s = track.count > 2 ? track.time_s[2] - track.time_s[1] : 1.0;
  return track.time_s[1] - segment_s;
}

}  // namespace

void derive(Track<Cartesian>& track, const Cartesian* joins) {
  const int n = track.count;
  auto& w = track.waypoints;
  if ((track.fields & COMPLY_FIELD_VELOCITY) == 0) {
    std::array<Vector3d, kTrackWaypoints> linear;
    impliedVelocities(
        track.time_s, 1, n, [&](int k) { return Vector3d(ConstVector3Map(w[k].position)); },
        linear.data());
    // Angular: the same rule on each segment's mean angular velocity (base frame).
    std::array<Vector3d, kTrackWaypoints> segment;
    for (int k = 1; k + 1 < n; ++k) {
      segment[k] = orientationError(fromXyzw(w[k].orientation), fromXyzw(w[k + 1].orientation)) /
                   (track.time_s[k + 1] - track.time_s[k]);
    }
    for (int k = 1; k < n; ++k) {
      Vector3d angular = Vector3d::Zero();
      if (k == 1 && n > 2) {
        angular = segment[1];
      } else if (k > 1 && k < n - 1) {
        const double before = track.time_s[k] - track.time_s[k - 1];
        const double after = track.time_s[k + 1] - track.time_s[k];
        angular = (after * segment[k - 1] + before * segment[k]) / (before + after);
      }
      Eigen::Map<Vector6d> twist(w[k].twist);
      twist << linear[k], angular;
    }
    if (const int k = joiningWaypoint(track); joins != nullptr && k > 0) {
      std::copy_n(joins->twist, 6, w[k].twist);
    }
  }
  // The lead-in: at rest, half a segment's travel at the first waypoint's velocity behind it.
  const double lead_s = track.time_s[1] - leadInTime(track);
  const Eigen::Quaterniond first = fromXyzw(w[1].orientation);
  const Vector3d first_body_rate = first.toRotationMatrix().transpose() * Vector3d(w[1].twist + 3);
  track.time_s[0] = leadInTime(track);
  w[0] = w[1];
  Vector3Map(w[0].position) = ConstVector3Map(w[1].position) - 0.5 * lead_s * Vector3d(w[1].twist);
  toXyzw((first * quaternionExp(-0.5 * lead_s * first_body_rate)).normalized(), w[0].orientation);
  Eigen::Map<Vector6d>(w[0].twist).setZero();

  for (int k = 0; k + 1 < n; ++k) {
    const Eigen::Quaterniond q0 = fromXyzw(w[k].orientation);
    const Eigen::Quaterniond q1 = fromXyzw(w[k + 1].orientation);
    Eigen::Quaterniond relative = q0.conjugate() * q1;
    if (relative.w() < 0.0) {
      relative.coeffs() = -relative.coeffs();
    }
    RotationSegment& rotation = track.rotation[k];
    const double length = track.time_s[k + 1] - track.time_s[k];
    rotation.phi = quaternionLog(relative);
    rotation.slope0 = length * (q0.toRotationMatrix().transpose() * Vector3d(w[k].twist + 3));
    rotation.slope1 = length * rightJacobianInverse(rotation.phi) *
                      (q1.toRotationMatrix().transpose() * Vector3d(w[k + 1].twist + 3));
  }
}

void derive(Track<Joint>& track, const Joint* joins) {
  auto& w = track.waypoints;
  const int dof = w[1].dof;
  if ((track.fields & COMPLY_FIELD_VELOCITY) == 0) {
    std::array<Eigen::VectorXd, kTrackWaypoints> velocity;
    impliedVelocities(
        track.time_s, 1, track.count,
        [&](int k) {
          return Eigen::VectorXd(Eigen::Map<const Eigen::VectorXd>(w[k].position, dof));
        },
        velocity.data());
    for (int k = 1; k < track.count; ++k) {
      std::copy_n(velocity[k].data(), dof, w[k].velocity);
    }
    if (const int k = joiningWaypoint(track); joins != nullptr && k > 0) {
      std::copy_n(joins->velocity, dof, w[k].velocity);
    }
  }
  const double lead_s = track.time_s[1] - leadInTime(track);
  track.time_s[0] = leadInTime(track);
  w[0] = w[1];
  for (int j = 0; j < dof; ++j) {
    w[0].position[j] = w[1].position[j] - 0.5 * lead_s * w[1].velocity[j];
    w[0].velocity[j] = 0.0;
  }
}

// ---- evaluated in the cycle --------------------------------------------------------------------

CartesianMotion motionAt(const Track<Cartesian>& track, const Place& place) noexcept {
  const Cartesian& a = track.waypoints[place.index];
  CartesianMotion motion;
  if (place.length_s == 0.0) {  // holding an end, at rest
    motion.position = ConstVector3Map(a.position);
    motion.orientation = fromXyzw(a.orientation);
    return motion;
  }
  const Cartesian& b = track.waypoints[place.index + 1];
  const double h = place.length_s;
  const curve::HermiteWeights w = curve::hermite(place.fraction);
  const ConstVector3Map p0(a.position);
  const ConstVector3Map p1(b.position);
  const ConstVector3Map v0(a.twist);
  const ConstVector3Map v1(b.twist);
  motion.position = w.value[0] * p0 + w.value[1] * h * v0 + w.value[2] * p1 + w.value[3] * h * v1;
  motion.velocity =
      (w.first[0] * p0 + w.first[1] * h * v0 + w.first[2] * p1 + w.first[3] * h * v1) / h;
  motion.acceleration =
      (w.second[0] * p0 + w.second[1] * h * v0 + w.second[2] * p1 + w.second[3] * h * v1) / (h * h);

  const RotationSegment& r = track.rotation[place.index];
  const Vector3d phi = w.value[1] * r.slope0 + w.value[2] * r.phi + w.value[3] * r.slope1;
  const Vector3d dphi = (w.first[1] * r.slope0 + w.first[2] * r.phi + w.first[3] * r.slope1) / h;
  const Vector3d ddphi =
      (w.second[1] * r.slope0 + w.second[2] * r.phi + w.second[3] * r.slope1) / (h * h);
  motion.orientation = (fromXyzw(a.orientation) * quaternionExp(phi)).normalized();
  // d/dt (R J_r dphi) = R (J_r ddphi + dJ_r/dt dphi): the second term, quadratic in the
  // segment's rate, is left out of the acceleration (a feedforward, not the path).
  const Eigen::Matrix3d to_base = motion.orientation.toRotationMatrix() * rightJacobian(phi);
  motion.angular_velocity = to_base * dphi;
  motion.angular_acceleration = to_base * ddphi;
  return motion;
}

JointMotion motionAt(const Track<Joint>& track, const Place& place) noexcept {
  const Joint& a = track.waypoints[place.index];
  const int dof = a.dof;
  JointMotion motion;
  motion.position = Eigen::Map<const Eigen::VectorXd>(a.position, dof);
  motion.velocity.setZero(dof);
  motion.acceleration.setZero(dof);
  if (place.length_s == 0.0) {
    return motion;
  }
  const Joint& b = track.waypoints[place.index + 1];
  const double h = place.length_s;
  const curve::HermiteWeights w = curve::hermite(place.fraction);
  for (int j = 0; j < dof; ++j) {
    const double p0 = a.position[j];
    const double p1 = b.position[j];
    const double m0 = h * a.velocity[j];
    const double m1 = h * b.velocity[j];
    motion.position[j] = w.value[0] * p0 + w.value[1] * m0 + w.value[2] * p1 + w.value[3] * m1;
    motion.velocity[j] =
        (w.first[0] * p0 + w.first[1] * m0 + w.first[2] * p1 + w.first[3] * m1) / h;
    motion.acceleration[j] =
        (w.second[0] * p0 + w.second[1] * m0 + w.second[2] * p1 + w.second[3] * m1) / (h * h);
  }
  return motion;
}

void settingsAt(const Track<Cartesian>& track, const Place& place, Cartesian& to) noexcept {
  const Cartesian& a = track.waypoints[place.index];
  const Cartesian& b = place.length_s > 0.0 ? track.waypoints[place.index + 1] : a;
  const double u = place.fraction;
  const int dof = a.dof;
  lerp(a.stiffness_translational, b.stiffness_translational, u, 9, to.stiffness_translational);
  lerp(a.stiffness_rotational, b.stiffness_rotational, u, 9, to.stiffness_rotational);
  lerp(a.damping_translational, b.damping_translational, u, 9, to.damping_translational);
  lerp(a.damping_rotational, b.damping_rotational, u, 9, to.damping_rotational);
  lerp(a.damping_ratio, b.damping_ratio, u, 6, to.damping_ratio);
  to.damping_mode = a.damping_mode;
  toXyzw(slerpShort(fromXyzw(a.task_frame), fromXyzw(b.task_frame), u), to.task_frame);
  lerp(a.wrench_feedforward, b.wrench_feedforward, u, 6, to.wrench_feedforward);
  lerp(a.torque_feedforward, b.torque_feedforward, u, dof, to.torque_feedforward);
  lerp(a.nullspace_position, b.nullspace_position, u, dof, to.nullspace_position);
  lerp(a.nullspace_stiffness, b.nullspace_stiffness, u, dof, to.nullspace_stiffness);
  lerp(a.nullspace_damping, b.nullspace_damping, u, dof, to.nullspace_damping);
}

void settingsAt(const Track<Joint>& track, const Place& place, Joint& to) noexcept {
  const Joint& a = track.waypoints[place.index];
  const Joint& b = place.length_s > 0.0 ? track.waypoints[place.index + 1] : a;
  const double u = place.fraction;
  lerp(a.stiffness, b.stiffness, u, a.dof, to.stiffness);
  lerp(a.damping, b.damping, u, a.dof, to.damping);
  lerp(a.torque_feedforward, b.torque_feedforward, u, a.dof, to.torque_feedforward);
}

}  // namespace comply::pipeline::chunk
