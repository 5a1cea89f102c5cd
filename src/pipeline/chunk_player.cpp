#include "comply/pipeline/chunk_player.hpp"

#include <algorithm>
#include <cmath>

#include "chunk_curve.hpp"
#include "comply/core/rotation.hpp"
#include "comply/schema/schema.hpp"

namespace comply::pipeline {
namespace {

using Cartesian = comply_cartesian_command;
using Joint = comply_joint_command;
using Eigen::Vector3d;
using Vector3Map = Eigen::Map<Vector3d>;
using ConstVector3Map = Eigen::Map<const Vector3d>;

constexpr std::uint8_t kFree = 0;
constexpr std::uint8_t kLoaded = 1;

Eigen::Quaterniond quaternionOf(const double* xyzw) noexcept {
  return {xyzw[3], xyzw[0], xyzw[1], xyzw[2]};
}
void store(const Eigen::Quaterniond& q, double* xyzw) noexcept {
  xyzw[0] = q.x();
  xyzw[1] = q.y();
  xyzw[2] = q.z();
  xyzw[3] = q.w();
}

/// to = a + (b - a) * fraction, entry by entry.
void lerp(const double* a, const double* b, double fraction, int size, double* to) noexcept {
  for (int i = 0; i < size; ++i) {
    to[i] = a[i] + (b[i] - a[i]) * fraction;
  }
}

Eigen::Quaterniond slerpShort(const Eigen::Quaterniond& a, const Eigen::Quaterniond& b,
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

/// Where `t_s` falls: waypoint `index` and the fraction of the segment after it (0 before the
/// first waypoint, 1 after the last: the chunk holds its ends).
struct Place {
  int index = 0;
  double fraction = 0.0;
  double length_s = 0.0;  ///< the segment's length, 0 when holding an end
};

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

/// The lead-in's time: one segment before the first waypoint (1 s for a chunk of one).
template <typename Bus>
double leadInTime(const Track<Bus>& track) {
  const double segment_s = track.count > 2 ? track.time_s[2] - track.time_s[1] : 1.0;
  return track.time_s[1] - segment_s;
}

void deriveVelocities(Track<Cartesian>& track) {
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
      segment[k] =
          orientationError(quaternionOf(w[k].orientation), quaternionOf(w[k + 1].orientation)) /
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
  }
  // The lead-in: at rest, half a segment's travel at the first waypoint's velocity behind it.
  const double lead_s = track.time_s[1] - leadInTime(track);
  const Eigen::Quaterniond first = quaternionOf(w[1].orientation);
  const Vector3d first_body_rate = first.toRotationMatrix().transpose() * Vector3d(w[1].twist + 3);
  track.time_s[0] = leadInTime(track);
  w[0] = w[1];
  Vector3Map(w[0].position) = ConstVector3Map(w[1].position) - 0.5 * lead_s * Vector3d(w[1].twist);
  store((first * curve::expRotation(-0.5 * lead_s * first_body_rate)).normalized(),
        w[0].orientation);
  Eigen::Map<Vector6d>(w[0].twist).setZero();

  for (int k = 0; k + 1 < n; ++k) {
    const Eigen::Quaterniond q0 = quaternionOf(w[k].orientation);
    const Eigen::Quaterniond q1 = quaternionOf(w[k + 1].orientation);
    Eigen::Quaterniond relative = q0.conjugate() * q1;
    if (relative.w() < 0.0) {
      relative.coeffs() = -relative.coeffs();
    }
    RotationSegment& rotation = track.rotation[k];
    const double length = track.time_s[k + 1] - track.time_s[k];
    rotation.phi = quaternionLog(relative);
    rotation.slope0 = length * (q0.toRotationMatrix().transpose() * Vector3d(w[k].twist + 3));
    rotation.slope1 = length * curve::rightJacobianInverse(rotation.phi) *
                      (q1.toRotationMatrix().transpose() * Vector3d(w[k + 1].twist + 3));
  }
}

void deriveVelocities(Track<Joint>& track) {
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

CartesianMotion motionAt(const Track<Cartesian>& track, double t_s, int& cursor) noexcept {
  const Place place = placeOf(track, t_s, cursor);
  const Cartesian& a = track.waypoints[place.index];
  CartesianMotion motion;
  if (place.length_s == 0.0) {  // holding an end, at rest
    motion.position = ConstVector3Map(a.position);
    motion.orientation = quaternionOf(a.orientation);
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
  motion.orientation = (quaternionOf(a.orientation) * curve::expRotation(phi)).normalized();
  // d/dt (R J_r dphi) = R (J_r ddphi + dJ_r/dt dphi): the second term, quadratic in the
  // segment's rate, is left out of the acceleration (a feedforward, not the path).
  const Eigen::Matrix3d to_base = motion.orientation.toRotationMatrix() * curve::rightJacobian(phi);
  motion.angular_velocity = to_base * dphi;
  motion.angular_acceleration = to_base * ddphi;
  return motion;
}

JointMotion motionAt(const Track<Joint>& track, double t_s, int& cursor) noexcept {
  const Place place = placeOf(track, t_s, cursor);
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

/// The chunk's gains, feedforward, task frame and nullspace at a place, written into `to`:
/// linear between the segment's waypoints, the task frame by spherical interpolation.
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
  store(slerpShort(quaternionOf(a.task_frame), quaternionOf(b.task_frame), u), to.task_frame);
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

/// Fades the groups `fields` of `chunk` in from `from` (fraction 0: all `from`, 1: all chunk)
/// into `active`.
void fadeSettings(const Cartesian& from, const Cartesian& chunk, std::uint32_t fields,
                  double fraction, Cartesian& active) noexcept {
  const int dof = active.dof;
  if ((fields & COMPLY_FIELD_STIFFNESS) != 0) {
    lerp(from.stiffness_translational, chunk.stiffness_translational, fraction, 9,
         active.stiffness_translational);
    lerp(from.stiffness_rotational, chunk.stiffness_rotational, fraction, 9,
         active.stiffness_rotational);
  }
  if ((fields & COMPLY_FIELD_DAMPING) != 0) {
    // Blocks of two modes mean different things: a change of mode takes effect at once.
    const double f = from.damping_mode == chunk.damping_mode ? fraction : 1.0;
    lerp(from.damping_translational, chunk.damping_translational, f, 9,
         active.damping_translational);
    lerp(from.damping_rotational, chunk.damping_rotational, f, 9, active.damping_rotational);
    lerp(from.damping_ratio, chunk.damping_ratio, f, 6, active.damping_ratio);
    active.damping_mode = chunk.damping_mode;
  }
  if ((fields & COMPLY_FIELD_TASK_FRAME) != 0) {
    store(slerpShort(quaternionOf(from.task_frame), quaternionOf(chunk.task_frame), fraction),
          active.task_frame);
  }
  if ((fields & COMPLY_FIELD_WRENCH_FEEDFORWARD) != 0) {
    lerp(from.wrench_feedforward, chunk.wrench_feedforward, fraction, 6, active.wrench_feedforward);
  }
  if ((fields & COMPLY_FIELD_TORQUE_FEEDFORWARD) != 0) {
    lerp(from.torque_feedforward, chunk.torque_feedforward, fraction, dof,
         active.torque_feedforward);
  }
  if ((fields & COMPLY_FIELD_NULLSPACE) != 0) {
    lerp(from.nullspace_position, chunk.nullspace_position, fraction, dof,
         active.nullspace_position);
    lerp(from.nullspace_stiffness, chunk.nullspace_stiffness, fraction, dof,
         active.nullspace_stiffness);
    lerp(from.nullspace_damping, chunk.nullspace_damping, fraction, dof, active.nullspace_damping);
  }
}

void fadeSettings(const Joint& from, const Joint& chunk, std::uint32_t fields, double fraction,
                  Joint& active) noexcept {
  if ((fields & COMPLY_FIELD_STIFFNESS) != 0) {
    lerp(from.stiffness, chunk.stiffness, fraction, active.dof, active.stiffness);
  }
  if ((fields & COMPLY_FIELD_DAMPING) != 0) {
    lerp(from.damping, chunk.damping, fraction, active.dof, active.damping);
  }
  if ((fields & COMPLY_FIELD_TORQUE_FEEDFORWARD) != 0) {
    lerp(from.torque_feedforward, chunk.torque_feedforward, fraction, active.dof,
         active.torque_feedforward);
  }
}

/// The difference between the reference in force and the chunk when the chunk starts, in value,
/// velocity and acceleration, which the blend lets decay to zero.
struct CartesianOffset {
  Vector3d position[3];
  Vector3d rotation[3];  ///< rotation vector (base frame) from the chunk's orientation to the old
};
struct JointOffset {
  JointVector position[3];
};

CartesianOffset offsetAt(const Cartesian& from, const CartesianMotion& chunk) noexcept {
  CartesianOffset offset;
  offset.position[0] = ConstVector3Map(from.position) - chunk.position;
  offset.position[1] = ConstVector3Map(from.twist) - chunk.velocity;
  offset.position[2] = ConstVector3Map(from.acceleration) - chunk.acceleration;
  // orientationError(a, b) is the base-frame rotation vector taking a to b.
  offset.rotation[0] = orientationError(chunk.orientation, quaternionOf(from.orientation));
  offset.rotation[1] = ConstVector3Map(from.twist + 3) - chunk.angular_velocity;
  offset.rotation[2] = ConstVector3Map(from.acceleration + 3) - chunk.angular_acceleration;
  return offset;
}

JointOffset offsetAt(const Joint& from, const JointMotion& chunk) noexcept {
  const int dof = from.dof;
  JointOffset offset;
  offset.position[0] = Eigen::Map<const Eigen::VectorXd>(from.position, dof) - chunk.position;
  offset.position[1] = Eigen::Map<const Eigen::VectorXd>(from.velocity, dof) - chunk.velocity;
  offset.position[2] =
      Eigen::Map<const Eigen::VectorXd>(from.acceleration, dof) - chunk.acceleration;
  return offset;
}

/// value, d/dt, d^2/dt^2 of a decaying offset `e` at blend fraction s of a blend of `length_s`.
template <typename Value>
void decay(const Value (&e)[3], const curve::QuinticWeights& w, double length_s, Value (&out)[3]) {
  const double t = length_s;
  out[0] = w.value[0] * e[0] + t * w.value[1] * e[1] + t * t * w.value[2] * e[2];
  out[1] = (w.first[0] * e[0] + t * w.first[1] * e[1] + t * t * w.first[2] * e[2]) / t;
  out[2] = (w.second[0] * e[0] + t * w.second[1] * e[1] + t * t * w.second[2] * e[2]) / (t * t);
}

void writeMotion(const CartesianMotion& m, Cartesian& to) noexcept {
  Vector3Map(to.position) = m.position;
  store(m.orientation, to.orientation);
  Eigen::Map<Vector6d>(to.twist) << m.velocity, m.angular_velocity;
  Eigen::Map<Vector6d>(to.acceleration) << m.acceleration, m.angular_acceleration;
}

void writeMotion(const JointMotion& m, Joint& to) noexcept {
  const int dof = to.dof;
  std::copy_n(m.position.data(), dof, to.position);
  std::copy_n(m.velocity.data(), dof, to.velocity);
  std::copy_n(m.acceleration.data(), dof, to.acceleration);
}

void addOffset(const CartesianOffset& e, const curve::QuinticWeights& w, double length_s,
               CartesianMotion& m) noexcept {
  Vector3d position[3];
  Vector3d rotation[3];
  decay(e.position, w, length_s, position);
  decay(e.rotation, w, length_s, rotation);
  m.position += position[0];
  m.velocity += position[1];
  m.acceleration += position[2];
  // The rotation's rates add as vectors: exact at the start, where the rate of the offset's
  // exponential equals the offset's rate only to first order in its angle, and the offset is
  // small when a chunk continues the one before it.
  m.orientation = (curve::expRotation(rotation[0]) * m.orientation).normalized();
  m.angular_velocity += rotation[1];
  m.angular_acceleration += rotation[2];
}

void addOffset(const JointOffset& e, const curve::QuinticWeights& w, double length_s,
               JointMotion& m) noexcept {
  JointVector position[3];
  decay(e.position, w, length_s, position);
  m.position += position[0];
  m.velocity += position[1];
  m.acceleration += position[2];
}

template <typename Bus>
struct Offset;
template <>
struct Offset<Cartesian> {
  using Type = CartesianOffset;
};
template <>
struct Offset<Joint> {
  using Type = JointOffset;
};

/// The typed half of the player: its slots and the running chunk's blend.
template <typename Bus>
struct Engine {
  std::array<Track<Bus>, ChunkPlayer::kSlots> tracks;
  Bus from{};  ///< the reference in force when the running chunk started
  typename Offset<Bus>::Type offset{};
  double start_s = 0.0;
  int cursor = 0;
  Bus settings{};  // scratch: the chunk's settings at this cycle's place
};

}  // namespace

struct ChunkPlayer::Slots {
  int kind = COMPLY_COMMAND_CARTESIAN;
  int dof = 0;
  double blend_time_s = 0.0;
  std::array<std::atomic<std::uint8_t>, kSlots> state{};
  std::unique_ptr<Engine<Cartesian>> cartesian;
  std::unique_ptr<Engine<Joint>> joint;

  int acquire() noexcept {
    for (int slot = 0; slot < kSlots; ++slot) {
      if (state[slot].load(std::memory_order_acquire) == kFree) {
        return slot;
      }
    }
    return -1;
  }
};

namespace {

template <typename Bus, typename Command>
int loadInto(ChunkPlayer::Slots& slots, Engine<Bus>& engine, const Chunk<Command>& chunk,
             double host_to_controller_s) {
  const int slot = slots.acquire();
  if (slot < 0) {
    return -1;
  }
  Track<Bus>& track = engine.tracks[slot];
  track.count = static_cast<int>(chunk.waypoints.size()) + 1;  // after the lead-in
  track.fields = static_cast<std::uint32_t>(chunk.fields);
  track.stamp_s = chunk.stamp_s;
  for (int k = 1; k < track.count; ++k) {
    const ChunkWaypoint<Command>& waypoint = chunk.waypoints[k - 1];
    track.time_s[k] = waypoint.time_s + host_to_controller_s;
    track.waypoints[k] = schema::toBus(waypoint.command, slots.dof);
  }
  deriveVelocities(track);
  slots.state[slot].store(kLoaded, std::memory_order_release);
  return slot;
}

template <typename Bus>
void startIn(Engine<Bus>& engine, int slot, const Bus& in_force, double now_s) noexcept {
  engine.from = in_force;
  engine.start_s = now_s;
  engine.cursor = 0;
  engine.offset = offsetAt(in_force, motionAt(engine.tracks[slot], now_s, engine.cursor));
}

/// Returns whether the chunk still runs after `now_s`.
template <typename Bus>
bool playIn(Engine<Bus>& engine, int slot, double blend_time_s, double now_s,
            Bus& active) noexcept {
  const Track<Bus>& track = engine.tracks[slot];
  auto motion = motionAt(track, now_s, engine.cursor);
  const double since_start = now_s - engine.start_s;
  const bool blending = blend_time_s > 0.0 && since_start < blend_time_s;
  double fraction = 1.0;
  if (blending) {
    const curve::QuinticWeights w = curve::quinticDecay(std::max(0.0, since_start) / blend_time_s);
    addOffset(engine.offset, w, blend_time_s, motion);
    fraction = 1.0 - w.value[0];
  }
  writeMotion(motion, active);
  const std::uint32_t settings = track.fields & ~(COMPLY_FIELD_POSITION | COMPLY_FIELD_VELOCITY);
  if (settings != 0) {
    int cursor = engine.cursor;
    settingsAt(track, placeOf(track, now_s, cursor), engine.settings);
    fadeSettings(engine.from, engine.settings, settings, fraction, active);
  }
  active.stamp_s = track.stamp_s;
  return blending || now_s < track.time_s[track.count - 1];
}

}  // namespace

ChunkPlayer::ChunkPlayer(int command_kind, int dof, double blend_time_s)
    : slots_(std::make_unique<Slots>()) {
  slots_->kind = command_kind;
  slots_->dof = dof;
  slots_->blend_time_s = std::max(0.0, blend_time_s);
  if (command_kind == COMPLY_COMMAND_CARTESIAN) {
    slots_->cartesian = std::make_unique<Engine<Cartesian>>();
  } else {
    slots_->joint = std::make_unique<Engine<Joint>>();
  }
}

ChunkPlayer::~ChunkPlayer() = default;

int ChunkPlayer::load(const CartesianChunk& chunk, double host_to_controller_s) {
  return slots_->cartesian ? loadInto(*slots_, *slots_->cartesian, chunk, host_to_controller_s)
                           : -1;
}

int ChunkPlayer::load(const JointChunk& chunk, double host_to_controller_s) {
  return slots_->joint ? loadInto(*slots_, *slots_->joint, chunk, host_to_controller_s) : -1;
}

void ChunkPlayer::release(int slot) noexcept {
  if (slot >= 0 && slot < kSlots) {
    slots_->state[slot].store(kFree, std::memory_order_release);
  }
}

void ChunkPlayer::start(int slot, const CommandBus& in_force, double now_s) noexcept {
  if (slot < 0 || slot >= kSlots) {
    return;
  }
  if (playing_ >= 0 && playing_ != slot) {
    release(playing_);
  }
  playing_ = slot;
  // get_if: the buses are of the player's kind (one controller), and the cycle must not throw.
  if (const auto* cartesian = std::get_if<Cartesian>(&in_force); slots_->cartesian && cartesian) {
    startIn(*slots_->cartesian, slot, *cartesian, now_s);
  } else if (const auto* joint = std::get_if<Joint>(&in_force); slots_->joint && joint) {
    startIn(*slots_->joint, slot, *joint, now_s);
  } else {
    stop();
  }
}

bool ChunkPlayer::play(double now_s, CommandBus& active) noexcept {
  if (playing_ < 0) {
    return false;
  }
  bool running = false;
  if (auto* cartesian = std::get_if<Cartesian>(&active); slots_->cartesian && cartesian) {
    running = playIn(*slots_->cartesian, playing_, slots_->blend_time_s, now_s, *cartesian);
  } else if (auto* joint = std::get_if<Joint>(&active); slots_->joint && joint) {
    running = playIn(*slots_->joint, playing_, slots_->blend_time_s, now_s, *joint);
  }
  if (!running) {
    stop();
  }
  return running;
}

void ChunkPlayer::stop() noexcept {
  release(playing_);
  playing_ = -1;
}

std::uint32_t ChunkPlayer::fields() const noexcept {
  if (playing_ < 0) {
    return 0;
  }
  return slots_->cartesian ? slots_->cartesian->tracks[playing_].fields
                           : slots_->joint->tracks[playing_].fields;
}

double ChunkPlayer::stamp() const noexcept {
  if (playing_ < 0) {
    return 0.0;
  }
  return slots_->cartesian ? slots_->cartesian->tracks[playing_].stamp_s
                           : slots_->joint->tracks[playing_].stamp_s;
}

}  // namespace comply::pipeline
