// Recursive kinematics and dynamics of a serial chain, all in base-frame coordinates.
//
// Spatial vectors are Plücker coordinates at the base origin, angular part first: a motion
// (w, v_O) and a force (n_O, f). A body's spatial inertia about the base origin is stored as
// (mass m, first moment h = m c, rotational inertia I_O about the origin), which acts on a motion
// as I (w, v) = (I_O w + h x v, m v - h x w) (Featherstone, Rigid Body Dynamics Algorithms, 2.13).
// Working in the base frame lets every joint reuse the same axis and origin that the Jacobian
// needs, so one forward pass serves pose, Jacobian, gravity, RNEA and CRBA.

#include "comply/model/update.hpp"

#include <cmath>

#include "joint_trig.hpp"

namespace comply::model {
namespace {

struct Motion {
  Eigen::Vector3d angular;
  Eigen::Vector3d linear;
};

struct Force {
  Eigen::Vector3d moment;
  Eigen::Vector3d force;
};

struct SpatialInertia {
  double mass;
  Eigen::Vector3d first_moment;
  Eigen::Matrix3d rotational;  // about the base origin

  Force apply(const Motion& m) const {
    return {rotational * m.angular + first_moment.cross(m.linear),
            mass * m.linear - first_moment.cross(m.angular)};
  }
};

/// Motion cross product (v x m): the rate of change of m when it moves with velocity v.
Motion crossMotion(const Motion& v, const Motion& m) {
  return {v.angular.cross(m.angular), v.angular.cross(m.linear) + v.linear.cross(m.angular)};
}

/// Force cross product (v x* f).
Force crossForce(const Motion& v, const Force& f) {
  return {v.angular.cross(f.moment) + v.linear.cross(f.force), v.angular.cross(f.force)};
}

double dot(const Motion& m, const Force& f) {
  return m.angular.dot(f.moment) + m.linear.dot(f.force);
}

/// A 3-vector in four lanes (the fourth zero): one AVX register.
using Lanes4 = double __attribute__((vector_size(32)));

/// r v for a rotation held as three column vectors.
template <typename Vector>
Lanes4 apply(const Lanes4 (&r)[3], const Vector& v) {
  return r[0] * v[0] + r[1] * v[1] + r[2] * v[2];
}

template <typename Vector>
Lanes4 load4(const Vector& v) {
  return Lanes4{v[0], v[1], v[2], 0.0};
}

/// (y, z, x) and (z, x, y) of a 3-vector: GCC's and clang's spellings of the same shuffle.
#if defined(__clang__)
Lanes4 yzx(const Lanes4& v) {
  return __builtin_shufflevector(v, v, 1, 2, 0, 3);
}
Lanes4 zxy(const Lanes4& v) {
  return __builtin_shufflevector(v, v, 2, 0, 1, 3);
}
#else
Lanes4 yzx(const Lanes4& v) {
  using Index4 = long long __attribute__((vector_size(32)));
  return __builtin_shuffle(v, Index4{1, 2, 0, 3});
}
Lanes4 zxy(const Lanes4& v) {
  using Index4 = long long __attribute__((vector_size(32)));
  return __builtin_shuffle(v, Index4{2, 0, 1, 3});
}
#endif

Lanes4 cross(const Lanes4& a, const Lanes4& b) {
  return yzx(a) * zxy(b) - zxy(a) * yzx(b);
}

double dot3(const Lanes4& a, const Lanes4& b) {
  const Lanes4 product = a * b;
  return product[0] + product[1] + product[2];
}

template <typename Vector>
void store(const Lanes4& lanes, Vector&& v) {
  v[0] = lanes[0];
  v[1] = lanes[1];
  v[2] = lanes[2];
}

/// Motion subspace of a joint: unit twist of the child body, in base coordinates.
Motion jointMotion(const ChainBody& body, const Data::BodyState& state) {
  if (body.type == JointType::kRevolute) {
    return {state.axis, state.origin.cross(state.axis)};
  }
  return {Eigen::Vector3d::Zero(), state.axis};
}

SpatialInertia worldInertia(const ChainBody& body, const Data::BodyState& state) {
  return {body.mass_kg, body.mass_kg * state.com, state.inertia_about_base_origin};
}

/// Rotational inertia of every body about the base origin (parallel-axis theorem), shared by the
/// Coriolis and mass-matrix passes.
void computeWorldInertias(const Model& model, Data& data) {
  for (int i = 0; i < model.dof(); ++i) {
    const ChainBody& body = model.body(i);
    Data::BodyState& state = data.bodies[i];
    Lanes4 r[3];
    Lanes4 r_inertia[3];  // R I_com
    for (int k = 0; k < 3; ++k) {
      r[k] = load4(state.rotation.col(k));
    }
    for (int k = 0; k < 3; ++k) {
      r_inertia[k] = apply(r, body.inertia_com.col(k));
    }
    const Lanes4 c = load4(state.com);
    const double c_squared = dot3(c, c);
    for (int k = 0; k < 3; ++k) {
      // Column k of R I_com R^T + m (|c|^2 I - c c^T).
      Lanes4 column = r_inertia[0] * r[0][k] + r_inertia[1] * r[1][k] + r_inertia[2] * r[2][k] -
                      body.mass_kg * c * c[k];
      column[k] += body.mass_kg * c_squared;
      store(column, state.inertia_about_base_origin.col(k));
    }
  }
}

void forwardKinematics(const Model& model, Data& data, std::span<const double> q) {
  const int n = model.dof();
  double sine[kMaxDof];
  double cosine[kMaxDof];
  bool in_range = true;
  for (int i = 0; i < n; ++i) {
    in_range = in_range && std::abs(q[i]) <= kFastTrigLimit;
  }
  if (in_range) {
    jointSinCos(q.data(), n, sine, cosine);
  } else {
    for (int i = 0; i < n; ++i) {
      sine[i] = std::sin(q[i]);
      cosine[i] = std::cos(q[i]);
    }
  }
  // The chain runs in registers, one 4-lane vector per column (GCC's vector extension). With
  // Eigen's 3-vectors GCC packed columns into pairs on the stack, stored as a pair and a single
  // and read back as differently aligned pairs: store-to-load forwarding failed on every joint
  // (measured: half of this function's time).
  Lanes4 parent_rotation[3] = {{1.0, 0.0, 0.0, 0.0}, {0.0, 1.0, 0.0, 0.0}, {0.0, 0.0, 1.0, 0.0}};
  Lanes4 parent_origin = {};
  for (int i = 0; i < n; ++i) {
    const ChainBody& body = model.body(i);
    Lanes4 rotation[3];
    Lanes4 origin;
    if (body.type == JointType::kRevolute) {
      const double s = sine[body.user_index];
      const double c = cosine[body.user_index];
      origin = parent_origin + apply(parent_rotation, body.translation);
      if (body.axis == Eigen::Vector3d::UnitZ()) {
        // The common URDF case (every joint of the arms shipped here): R_parent R_const Rz(q)
        // mixes two columns, a third of the work of forming the Rodrigues terms and a product.
        const Lanes4 x = apply(parent_rotation, body.rotation_const.col(0));
        const Lanes4 y = apply(parent_rotation, body.rotation_const.col(1));
        rotation[0] = c * x + s * y;
        rotation[1] = c * y - s * x;
        rotation[2] = apply(parent_rotation, body.rotation_const.col(2));
      } else {
        const Eigen::Matrix3d local =
            body.rotation_const + s * body.rotation_sin + (1.0 - c) * body.rotation_cos;
        for (int k = 0; k < 3; ++k) {
          rotation[k] = apply(parent_rotation, local.col(k));
        }
      }
    } else {
      const double position = q[body.user_index];
      origin =
          parent_origin + apply(parent_rotation, body.translation + body.axis_in_parent * position);
      for (int k = 0; k < 3; ++k) {
        rotation[k] = apply(parent_rotation, body.rotation_const.col(k));
      }
    }
    Data::BodyState& state = data.bodies[i];
    store(apply(parent_rotation, body.axis_in_parent), state.axis);
    store(origin + apply(rotation, body.com), state.com);
    for (int k = 0; k < 3; ++k) {
      store(rotation[k], state.rotation.col(k));
      parent_rotation[k] = rotation[k];
    }
    store(origin, state.origin);
    parent_origin = origin;
  }
  const Eigen::Isometry3d& tip = model.tipInLastBody();
  for (int k = 0; k < 3; ++k) {
    store(apply(parent_rotation, tip.linear().col(k)), data.tip_rotation.col(k));
  }
  store(parent_origin + apply(parent_rotation, tip.translation()), data.tip_position);
}

void computeJacobian(const Model& model, Data& data) {
  for (int i = 0; i < model.dof(); ++i) {
    const ChainBody& body = model.body(i);
    const Data::BodyState& state = data.bodies[i];
    auto column = data.jacobian.col(body.user_index);
    if (body.type == JointType::kRevolute) {
      column.head<3>() = state.axis.cross(data.tip_position - state.origin);
      column.tail<3>() = state.axis;
    } else {
      column.head<3>() = state.axis;
      column.tail<3>().setZero();
    }
  }
}

/// g(q)_i = a_i . ((h_sub - m_sub p_i) x (-g)) for revolute joints, a_i . (-m_sub g) for prismatic,
/// where m_sub, h_sub are the mass and first moment of everything outboard of joint i.
void computeGravity(const Model& model, Data& data) {
  const Eigen::Vector3d weight_direction = -model.gravity();
  double outboard_mass = 0.0;
  Eigen::Vector3d outboard_first_moment = Eigen::Vector3d::Zero();
  for (int i = model.dof() - 1; i >= 0; --i) {
    const ChainBody& body = model.body(i);
    const Data::BodyState& state = data.bodies[i];
    outboard_mass += body.mass_kg;
    outboard_first_moment += body.mass_kg * state.com;
    if (body.type == JointType::kRevolute) {
      data.gravity[body.user_index] = state.axis.dot(
          (outboard_first_moment - outboard_mass * state.origin).cross(weight_direction));
    } else {
      data.gravity[body.user_index] = outboard_mass * state.axis.dot(weight_direction);
    }
  }
}

void computePayloadGravity(const Model& model, Data& data) {
  const Eigen::Vector3d payload_weight = -data.payload.mass_kg * model.gravity();
  const Eigen::Vector3d payload_com =
      data.tip_position + data.tip_rotation * data.payload.com_in_tip;
  for (int i = 0; i < model.dof(); ++i) {
    const ChainBody& body = model.body(i);
    const Data::BodyState& state = data.bodies[i];
    data.payload_gravity[body.user_index] =
        body.type == JointType::kRevolute
            ? state.axis.dot((payload_com - state.origin).cross(payload_weight))
            : state.axis.dot(payload_weight);
  }
}

/// Recursive Newton-Euler with zero acceleration and zero gravity: C(q, dq) dq.
void computeCoriolis(const Model& model, Data& data, std::span<const double> dq) {
  std::array<Motion, kMaxDof> subspace;
  std::array<Force, kMaxDof> body_force;
  Motion velocity{Eigen::Vector3d::Zero(), Eigen::Vector3d::Zero()};
  Motion acceleration{Eigen::Vector3d::Zero(), Eigen::Vector3d::Zero()};
  for (int i = 0; i < model.dof(); ++i) {
    const ChainBody& body = model.body(i);
    const Data::BodyState& state = data.bodies[i];
    subspace[i] = jointMotion(body, state);
    const double rate = dq[body.user_index];
    const Motion joint_velocity{subspace[i].angular * rate, subspace[i].linear * rate};
    // The axis moves with the parent, so d/dt(S dq) = v_parent x S dq when ddq = 0.
    const Motion bias = crossMotion(velocity, joint_velocity);
    acceleration.angular += bias.angular;
    acceleration.linear += bias.linear;
    velocity.angular += joint_velocity.angular;
    velocity.linear += joint_velocity.linear;
    const SpatialInertia inertia = worldInertia(body, state);
    const Force inertial = inertia.apply(acceleration);
    const Force gyroscopic = crossForce(velocity, inertia.apply(velocity));
    body_force[i] = {inertial.moment + gyroscopic.moment, inertial.force + gyroscopic.force};
  }
  Force outboard{Eigen::Vector3d::Zero(), Eigen::Vector3d::Zero()};
  for (int i = model.dof() - 1; i >= 0; --i) {
    outboard.moment += body_force[i].moment;
    outboard.force += body_force[i].force;
    data.coriolis[model.body(i).user_index] = dot(subspace[i], outboard);
  }
}

/// Composite-rigid-body algorithm: M_ji = S_j . (I^c_i S_i) for j <= i, plus the rotor inertias on
/// the diagonal. In 4-lane registers like the forward kinematics (the composite inertia is carried
/// from body to body).
void computeMassMatrix(const Model& model, Data& data) {
  Lanes4 angular[kMaxDof];  // motion subspace S_i = (a_i, o_i x a_i), or (0, a_i) if prismatic
  Lanes4 linear[kMaxDof];
  for (int i = 0; i < model.dof(); ++i) {
    const Data::BodyState& state = data.bodies[i];
    const Lanes4 axis = load4(state.axis);
    if (model.body(i).type == JointType::kRevolute) {
      angular[i] = axis;
      linear[i] = cross(load4(state.origin), axis);
    } else {
      angular[i] = Lanes4{};
      linear[i] = axis;
    }
  }
  double mass = 0.0;
  Lanes4 first_moment = {};
  Lanes4 rotational[3] = {};
  for (int i = model.dof() - 1; i >= 0; --i) {
    const ChainBody& body = model.body(i);
    const Data::BodyState& state = data.bodies[i];
    mass += body.mass_kg;
    first_moment += body.mass_kg * load4(state.com);
    for (int k = 0; k < 3; ++k) {
      rotational[k] += load4(state.inertia_about_base_origin.col(k));
    }
    // I S_i = (I_O a + h x v, m v - h x a) (Featherstone 2.13).
    const Lanes4 moment = apply(rotational, angular[i]) + cross(first_moment, linear[i]);
    const Lanes4 force = mass * linear[i] - cross(first_moment, angular[i]);
    const int row_i = body.user_index;
    for (int j = 0; j <= i; ++j) {
      const double value = dot3(angular[j], moment) + dot3(linear[j], force);
      const int row_j = model.body(j).user_index;
      data.mass_matrix(row_j, row_i) = value;
      data.mass_matrix(row_i, row_j) = value;
    }
    // The rotor spins with its joint's rate times the gear ratio: its inertia reflected through
    // the gear adds to this joint's own diagonal entry only.
    data.mass_matrix(row_i, row_i) += body.armature;
  }
}

bool allFinite(std::span<const double> values) {
  for (const double v : values) {
    if (!std::isfinite(v)) {
      return false;
    }
  }
  return true;
}

}  // namespace

UpdateStatus update(const Model& model, Data& data, std::span<const double> q,
                    std::span<const double> dq, Quantity requested) noexcept {
  const auto dof = static_cast<std::size_t>(model.dof());
  const bool needs_velocity = contains(requested, Quantity::kCoriolis);
  if (q.size() != dof || (needs_velocity && dq.size() != dof)) {
    return UpdateStatus::kSizeMismatch;
  }
  if (!allFinite(q) || (needs_velocity && !allFinite(dq))) {
    return UpdateStatus::kNonFinite;
  }

  forwardKinematics(model, data, q);
  if (contains(requested, Quantity::kPose)) {
    data.tip_orientation = Eigen::Quaterniond(data.tip_rotation);
    if (data.tip_orientation.w() < 0.0) {
      data.tip_orientation.coeffs() = -data.tip_orientation.coeffs();  // one hemisphere, w >= 0
    }
  }
  if (contains(requested, Quantity::kJacobian)) {
    computeJacobian(model, data);
  }
  if (contains(requested, Quantity::kGravity)) {
    computeGravity(model, data);
  }
  if (contains(requested, Quantity::kPayloadGravity)) {
    computePayloadGravity(model, data);
  }
  if (contains(requested, Quantity::kCoriolis) || contains(requested, Quantity::kMassMatrix)) {
    computeWorldInertias(model, data);
  }
  if (contains(requested, Quantity::kCoriolis)) {
    computeCoriolis(model, data, dq);
  }
  if (contains(requested, Quantity::kMassMatrix)) {
    computeMassMatrix(model, data);
  }
  data.computed = requested;
  return UpdateStatus::kOk;
}

}  // namespace comply::model
