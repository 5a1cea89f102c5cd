#include "comply/pipeline/contact_speed.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "comply/pipeline/wrench_bound.hpp"

namespace comply::pipeline {
namespace {

// Shares of v_max (contact_speed.hpp), the motion governor's for its TCP speed: the law's push
// along the motion fades from kShareFrom and is gone at kBrakeFrom, past which the TCP is braked.
constexpr double kShareFrom = 0.5;
constexpr double kBrakeFrom = 0.85;
// Slower than this the measured velocity's direction is noise, and no limit is near [m/s].
constexpr double kMovingSpeed = 1e-3;

constexpr int kStride = kMaxDof;  // ReflectedInertia::Lower is row-major kMaxDof wide

/// M + diag(rotors) = L D L^T into `lower` (L's strict lower triangle) and 1 / D_jj into
/// `inverse_pivot`, for n = N joints (loops the compiler unrolls, for the common arms) or, with
/// N = 0, `dof`. False where M + diag(rotors) is not positive definite.
template <int N>
bool factoriseLdl(const JointMatrix& m, const JointVector& rotors, int dof,
                  ReflectedInertia::Lower& lower, double* inverse_pivot) noexcept {
  const int n = N > 0 ? N : dof;
  const bool with_rotors = rotors.size() == n;
  double pivot[kMaxDof];
#pragma GCC unroll 12
  for (int j = 0; j < n; ++j) {
    double d = m(j, j) + (with_rotors ? rotors[j] : 0.0);
#pragma GCC unroll 12
    for (int k = 0; k < j; ++k) {
      d -= lower[j * kStride + k] * lower[j * kStride + k] * pivot[k];
    }
    if (!(d > 0.0)) {
      return false;
    }
    pivot[j] = d;
    inverse_pivot[j] = 1.0 / d;
#pragma GCC unroll 12
    for (int i = j + 1; i < n; ++i) {
      double sum = m(i, j);
#pragma GCC unroll 12
      for (int k = 0; k < j; ++k) {
        sum -= lower[i * kStride + k] * lower[j * kStride + k] * pivot[k];
      }
      lower[i * kStride + j] = sum * inverse_pivot[j];
    }
  }
  return true;
}

/// L^-1 `in` into `out` for n = N (or, with N = 0, `dof`) joints.
template <int N>
void forwardSubstitute(const ReflectedInertia::Lower& lower, int dof, const double* in,
                       double* out) noexcept {
  const int n = N > 0 ? N : dof;
#pragma GCC unroll 12
  for (int i = 0; i < n; ++i) {
    double sum = in[i];
#pragma GCC unroll 12
    for (int k = 0; k < i; ++k) {
      sum -= lower[i * kStride + k] * out[k];
    }
    out[i] = sum;
  }
}

/// J_v^T `direction` into `out` for N joints (or, with N = 0, `dof`): of fixed size, the product
/// is a few vector instructions; of the capacity-sized Jacobian, a call into Eigen's GEMV.
template <int N>
void translationalTranspose(const Jacobian& jacobian, int dof, const Eigen::Vector3d& direction,
                            double* out) noexcept {
  constexpr int kColumns = N > 0 ? N : Eigen::Dynamic;
  const Eigen::Map<const Eigen::Matrix<double, 6, kColumns>> full(jacobian.data(), 6, dof);
  Eigen::Map<Eigen::Matrix<double, kColumns, 1>>(out, dof).noalias() =
      full.template topRows<3>().transpose() * direction;
}

/// `along` . D^-1 L^-1 `in` for n = N (or, with N = 0, `dof`) joints: u^T J_v (L D L^T)^-1 in,
/// `along` being L^-1 J_v^T u.
template <int N>
double weightedAlong(const ReflectedInertia::Lower& lower, const double* inverse_pivot, int dof,
                     const double* along, const double* in) noexcept {
  const int n = N > 0 ? N : dof;
  double solved[kMaxDof];
  forwardSubstitute<N>(lower, dof, in, solved);
  double sum = 0.0;
#pragma GCC unroll 12
  for (int i = 0; i < n; ++i) {
    sum += along[i] * inverse_pivot[i] * solved[i];
  }
  return sum;
}

}  // namespace

bool ReflectedInertia::factorise(const model::Data& data, const JointVector& armature,
                                 int dof) noexcept {
  dof_ = dof;
  // The rotors are a mass a contact must stop as well (contact_speed.hpp): those the model's M
  // leaves out are added, else the mass would be too small and the limit too fast.
  const JointMatrix& m = data.mass_matrix;
  double* inverse = inverse_pivot_.data();
  factorised_ = dof == 7   ? factoriseLdl<7>(m, armature, dof, lower_, inverse)
                : dof == 6 ? factoriseLdl<6>(m, armature, dof, lower_, inverse)
                           : factoriseLdl<0>(m, armature, dof, lower_, inverse);
  return factorised_;
}

double ReflectedInertia::mass(const model::Data& data, const Eigen::Vector3d& direction) noexcept {
  if (!factorised_) {
    return std::numeric_limits<double>::infinity();
  }
  // u^T J_v (L D L^T)^-1 J_v^T u = sum_i y_i^2 / D_ii with y = L^-1 J_v^T u.
  double projected[kMaxDof];
  if (dof_ == 7) {
    translationalTranspose<7>(data.jacobian, dof_, direction, projected);
    forwardSubstitute<7>(lower_, dof_, projected, along_.data());
  } else if (dof_ == 6) {
    translationalTranspose<6>(data.jacobian, dof_, direction, projected);
    forwardSubstitute<6>(lower_, dof_, projected, along_.data());
  } else {
    translationalTranspose<0>(data.jacobian, dof_, direction, projected);
    forwardSubstitute<0>(lower_, dof_, projected, along_.data());
  }
  double inverse_mass = 0.0;
  for (int i = 0; i < dof_; ++i) {
    inverse_mass += along_[i] * along_[i] * inverse_pivot_[i];
  }
  return inverse_mass > 0.0 ? 1.0 / inverse_mass : std::numeric_limits<double>::infinity();
}

double ReflectedInertia::accelerationAlong(const JointVector& torque) const noexcept {
  if (!factorised_) {
    return 0.0;
  }
  const double* inverse = inverse_pivot_.data();
  return dof_ == 7   ? weightedAlong<7>(lower_, inverse, dof_, along_.data(), torque.data())
         : dof_ == 6 ? weightedAlong<6>(lower_, inverse, dof_, along_.data(), torque.data())
                     : weightedAlong<0>(lower_, inverse, dof_, along_.data(), torque.data());
}

double reflectedMass(const model::Data& data, const JointVector& armature, int dof,
                     const Eigen::Vector3d& direction) {
  ReflectedInertia inertia;
  (void)inertia.factorise(data, armature, dof);
  return inertia.mass(data, direction);
}

ContactSpeed::ContactSpeed(const CycleParameters& parameters, int dof, bool cartesian)
    : parameters_(parameters.contact_speed),
      effort_limit_(parameters.effort_limit),
      dof_(dof),
      enabled_(cartesian && parameters.contact_speed.enabled) {
  reset();
}

void ContactSpeed::reset() noexcept {
  limit_m_per_s_ = 0.0;
  mass_kg_ = 0.0;
  share_ = 1.0;
  brake_n_ = 0.0;
}

bool ContactSpeed::apply(const model::Data& data, const Vector6d& tcp_twist, double period_s,
                         JointVector& law_torque, JointVector& torque) noexcept {
  share_ = 1.0;
  brake_n_ = 0.0;
  const Eigen::Vector3d velocity = tcp_twist.head<3>();
  const double speed = velocity.norm();
  if (!enabled_ || !(period_s > 0.0) || !(speed > kMovingSpeed)) {
    return false;
  }
  const Eigen::Vector3d direction = velocity / speed;
  (void)inertia_.factorise(data, JointVector(), dof_);  // the laws' M(q): rotors included
  const double arm_kg = inertia_.mass(data, direction);
  // Infinite only for a model whose inertia is not positive definite: the TCP moves along u, so
  // J_v^T u is not zero. Nothing to bound by; the last limit stays reported.
  if (!std::isfinite(arm_kg)) {
    return false;
  }
  const double moving_kg = arm_kg + parameters_.payload_mass_kg;
  mass_kg_ = parameters_.body_mass_kg > 0.0
                 ? 1.0 / (1.0 / parameters_.body_mass_kg + 1.0 / moving_kg)
                 : moving_kg;
  limit_m_per_s_ = parameters_.force_limit_n / std::sqrt(mass_kg_ * parameters_.stiffness_n_per_m);
  // Only a law that accelerates the TCP toward the contact is scaled, never one that brakes
  // along u (what its torque adds to the acceleration along u, computed only here).
  if (speed > kShareFrom * limit_m_per_s_ && inertia_.accelerationAlong(law_torque) > 0.0) {
    share_ = std::clamp(
        (kBrakeFrom * limit_m_per_s_ - speed) / ((kBrakeFrom - kShareFrom) * limit_m_per_s_), 0.0,
        1.0);
    torque -= (1.0 - share_) * law_torque;
    law_torque *= share_;
  }
  const bool braked = brake(data, direction, speed, moving_kg, period_s, torque);
  return share_ < 1.0 || braked;
}

bool ContactSpeed::brake(const model::Data& data, const Eigen::Vector3d& direction, double speed,
                         double mass_kg, double period_s, JointVector& torque) noexcept {
  const double excess = speed - kBrakeFrom * limit_m_per_s_;
  if (!(excess > 0.0)) {
    return false;
  }
  // Half of deadbeat on the mass along u the force accelerates (the arm's, rotors included, and
  // the payload): stable on every heavier one.
  Vector6d wrench = Vector6d::Zero();
  wrench.head<3>() = -(mass_kg / (2.0 * period_s) * excess) * direction;
  (void)boundWrench(data.jacobian, wrench.data(), effort_limit_, dof_);
  brake_n_ = wrench.head<3>().norm();
  torque.head(dof_).noalias() += data.jacobian.leftCols(dof_).transpose() * wrench;
  return true;
}

}  // namespace comply::pipeline
