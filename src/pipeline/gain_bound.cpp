// The gains an arm renders stably (see gain_bound.hpp).

#include "comply/pipeline/gain_bound.hpp"

#include <Eigen/Cholesky>
#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <limits>
#include <random>
#include <sstream>
#include <vector>

#include "comply/model/data.hpp"
#include "comply/model/update.hpp"

namespace comply::pipeline {
namespace {

/// The largest eigenvalue of a symmetric 3x3 block (its stiffest axis).
double largestEigenvalue(const Eigen::Matrix3d& block) {
  return Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d>(block, Eigen::EigenvaluesOnly)
      .eigenvalues()
      .maxCoeff();
}

std::string number(double value) {
  std::ostringstream text;
  text.precision(3);
  text << value;
  return text.str();
}

Verdict refuse(const std::string& field, double value, const char* unit, double limit,
               const std::string& because) {
  return {false, RejectionReason::kInvalidGains,
          std::string(toString(RejectionReason::kInvalidGains)) + ": " + field + " " +
              number(value) + " " + unit + " is above what the arm renders stably, " +
              number(limit) + " " + unit + " (" + because + ")"};
}

/// What an inertia is called in a message, and its unit.
struct InertiaName {
  const char* name;
  const char* unit;
};
constexpr InertiaName kTcpMass{"apparent mass at the TCP", "kg"};
constexpr InertiaName kTcpInertia{"apparent rotational inertia at the TCP", "kg m^2"};
constexpr InertiaName kJointInertia{"inertia", "kg m^2"};

/// The torque-rate limit R a gain's torque passes through: joint i's, or for a Cartesian gain the
/// lowest joint's (its torque reaches every joint); infinite without a rate bound.
double rateOf(const GainBound& bound, Eigen::Index joint) {
  if (bound.torque_rate_limit.size() == 0 || !(bound.rate_limit_swing_nm > 0.0)) {
    return std::numeric_limits<double>::infinity();
  }
  return joint < 0 ? bound.torque_rate_limit.minCoeff() : bound.torque_rate_limit[joint];
}

/// K against m w_max^2, w_max = min(c / T, R / tau).
Verdict checkStiffness(const std::string& field, double stiffness, const char* unit, double inertia,
                       InertiaName inertia_name, const GainBound& bound, double period_s,
                       double rate) {
  const double sampled = bound.max_wn_period / period_s;
  const double rated = rate / bound.rate_limit_swing_nm;
  const double natural_frequency = std::min(sampled, rated);
  const double limit = inertia * natural_frequency * natural_frequency;
  if (stiffness <= limit) {
    return {};
  }
  const std::string frequency =
      rated < sampled
          ? "(" + number(rate) + " N m/s torque-rate limit / " + number(bound.rate_limit_swing_nm) +
                " N m swing)^2"
          : "(" + number(bound.max_wn_period) + " / " + number(period_s * 1e3) + " ms)^2";
  return refuse(field, stiffness, unit, limit,
                bound.robot + "'s lightest " + inertia_name.name + ", " + number(inertia) + " " +
                    inertia_name.unit + ", x " + frequency);
}

/// Absolute damping D against 2 c m / T.
Verdict checkDamping(const std::string& field, double damping, const char* unit, double inertia,
                     InertiaName inertia_name, const GainBound& bound, double period_s) {
  const double limit = 2.0 * bound.max_wn_period * inertia / period_s;
  if (damping <= limit) {
    return {};
  }
  return refuse(field, damping, unit, limit,
                "2 x " + number(bound.max_wn_period) + " x " + bound.robot + "'s lightest " +
                    inertia_name.name + ", " + number(inertia) + " " + inertia_name.unit + ", / " +
                    number(period_s * 1e3) + " ms");
}

/// A damping ratio zeta at stiffness K: zeta sqrt(K/m) T against c.
Verdict checkRatio(const std::string& field, double ratio, double stiffness, double inertia,
                   const GainBound& bound, double period_s) {
  if (stiffness <= 0.0) {
    return {};
  }
  const double limit = bound.max_wn_period / (std::sqrt(stiffness / inertia) * period_s);
  if (ratio <= limit) {
    return {};
  }
  return refuse(field, ratio, "", limit,
                "at a stiffness of " + number(stiffness) + " on " + bound.robot +
                    "'s lightest inertia " + number(inertia) +
                    ", zeta w_n T <= " + number(bound.max_wn_period));
}

/// joint_pd with a Cartesian law: the drive gains kp_i = J_i^T K J_i, kd_i = J_i^T D J_i at their
/// largest over the workspace, against joint i's lightest inertia (gain_bound.hpp).
Verdict checkDriveGains(const CartesianCommand& command, const GainBound& bound, double period_s) {
  const bool stiffness = has(command.fields, CommandField::kStiffness);
  const bool damping = has(command.fields, CommandField::kDamping);
  const double k_translational = largestEigenvalue(command.stiffness_translational);
  const double k_rotational = largestEigenvalue(command.stiffness_rotational);
  const bool ratio = command.damping_mode == DampingMode::kRatio;
  for (Eigen::Index i = 0; i < bound.joint_inertia.size(); ++i) {
    const std::string joint = std::to_string(i + 1);
    const double lever = bound.joint_lever_sq[i];
    const double axis = bound.joint_axis_sq[i];
    const double kp = k_translational * lever + k_rotational * axis;
    Verdict verdict;
    if (stiffness) {
      verdict = checkStiffness("joint_pd drive kp of joint " + joint + " (J^T K J at most)", kp,
                               "N m/rad", bound.joint_inertia[i], kJointInertia, bound, period_s,
                               rateOf(bound, i));
    }
    if (verdict.accepted && damping && !ratio) {
      const double kd = largestEigenvalue(command.damping_translational) * lever +
                        largestEigenvalue(command.damping_rotational) * axis;
      verdict = checkDamping("joint_pd drive kd of joint " + joint + " (J^T D J at most)", kd,
                             "N m s/rad", bound.joint_inertia[i], kJointInertia, bound, period_s);
    }
    if (verdict.accepted && (stiffness || damping) && ratio) {
      verdict =
          checkRatio("damping_ratio (mean, joint_pd drive of joint " + joint + ")",
                     command.damping_ratio.mean(), kp, bound.joint_inertia[i], bound, period_s);
    }
    if (!verdict.accepted) {
      return verdict;
    }
  }
  return {};
}

}  // namespace

GainBound lightestInertias(const model::Model& model, const JointVector& armature, int samples,
                           AddedInertia added) {
  const int dof = model.dof();
  GainBound bound;
  JointVector lower(dof);
  JointVector upper(dof);
  for (int i = 0; i < dof; ++i) {
    // A continuous joint (no limits) turns once: its configurations are all within a turn.
    const bool bounded =
        std::isfinite(model.limits(i).lower) && std::isfinite(model.limits(i).upper);
    lower[i] = bounded ? model.limits(i).lower : -M_PI;
    upper[i] = bounded ? model.limits(i).upper : M_PI;
  }
  model::Data data(model);
  std::mt19937 random(20261126);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  // The most the unit force (torque) accelerates the TCP, or a joint, anywhere: its inverse is
  // the lightest inertia along that direction.
  double max_translational = 0.0;
  double max_rotational = 0.0;
  JointVector max_joint = JointVector::Zero(dof);
  JointVector max_lever_sq = JointVector::Zero(dof);
  JointVector max_axis_sq = JointVector::Zero(dof);
  Vector6d added_diagonal;
  added_diagonal << Eigen::Vector3d::Constant(added.mass_kg),
      Eigen::Vector3d::Constant(added.inertia_kg_m2);
  const bool adds = added.mass_kg > 0.0 || added.inertia_kg_m2 > 0.0;
  JointVector q(dof);
  const JointVector zero = JointVector::Zero(dof);
  for (int sample = 0; sample <= samples; ++sample) {
    for (int i = 0; i < dof; ++i) {
      const double s = sample == 0 ? 0.5 : unit(random);
      q[i] = lower[i] + s * (upper[i] - lower[i]);
    }
    if (model::update(model, data, {q.data(), static_cast<std::size_t>(dof)},
                      {zero.data(), static_cast<std::size_t>(dof)},
                      model::Quantity::kJacobian | model::Quantity::kMassMatrix) !=
        model::UpdateStatus::kOk) {
      continue;
    }
    JointMatrix inertia = data.mass_matrix;
    if (armature.size() == dof) {
      inertia.diagonal() += armature;
    }
    if (adds) {
      inertia.noalias() += data.jacobian.transpose() * added_diagonal.asDiagonal() * data.jacobian;
    }
    max_lever_sq =
        max_lever_sq.cwiseMax(data.jacobian.topRows<3>().colwise().squaredNorm().transpose());
    max_axis_sq =
        max_axis_sq.cwiseMax(data.jacobian.bottomRows<3>().colwise().squaredNorm().transpose());
    const JointMatrix inverse = inertia.llt().solve(JointMatrix::Identity(dof, dof));
    const Eigen::Matrix<double, 6, 6> mobility =
        data.jacobian * inverse * data.jacobian.transpose();
    max_translational =
        std::max(max_translational, largestEigenvalue(mobility.topLeftCorner<3, 3>()));
    max_rotational =
        std::max(max_rotational, largestEigenvalue(mobility.bottomRightCorner<3, 3>()));
    max_joint = max_joint.cwiseMax(inverse.diagonal());
  }
  if (max_translational <= 0.0 || max_rotational <= 0.0 || (max_joint.array() <= 0.0).any()) {
    return bound;  // no configuration could be evaluated: no bound rather than a wrong one
  }
  bound.translational_mass_kg = 1.0 / max_translational;
  bound.rotational_inertia_kg_m2 = 1.0 / max_rotational;
  bound.joint_inertia = max_joint.cwiseInverse();
  bound.joint_lever_sq = max_lever_sq;
  bound.joint_axis_sq = max_axis_sq;
  return bound;
}

Verdict checkRenderable(const CartesianCommand& command, const GainBound& bound, double period_s) {
  if (!bound.enabled() || !(period_s > 0.0)) {
    return {};
  }
  const double m = bound.translational_mass_kg;
  const double inertia = bound.rotational_inertia_kg_m2;
  const double k_translational = largestEigenvalue(command.stiffness_translational);
  const double k_rotational = largestEigenvalue(command.stiffness_rotational);
  const bool stiffness = has(command.fields, CommandField::kStiffness);
  std::vector<Verdict> verdicts;
  if (stiffness) {
    verdicts.push_back(checkStiffness("stiffness_translational", k_translational, "N/m", m,
                                      kTcpMass, bound, period_s, rateOf(bound, -1)));
    verdicts.push_back(checkStiffness("stiffness_rotational", k_rotational, "N m/rad", inertia,
                                      kTcpInertia, bound, period_s, rateOf(bound, -1)));
  }
  const bool damping = has(command.fields, CommandField::kDamping);
  if (damping && command.damping_mode == DampingMode::kAbsolute) {
    verdicts.push_back(checkDamping("damping_translational",
                                    largestEigenvalue(command.damping_translational), "N s/m", m,
                                    kTcpMass, bound, period_s));
    verdicts.push_back(checkDamping("damping_rotational",
                                    largestEigenvalue(command.damping_rotational), "N m s/rad",
                                    inertia, kTcpInertia, bound, period_s));
  }
  // A ratio acts with the stiffness in force: checked when either of them changes (the caller
  // merges the command into the gains in force).
  if ((stiffness || damping) && command.damping_mode == DampingMode::kRatio) {
    verdicts.push_back(checkRatio("damping_ratio (translational)",
                                  command.damping_ratio.head<3>().maxCoeff(), k_translational, m,
                                  bound, period_s));
    verdicts.push_back(checkRatio("damping_ratio (rotational)",
                                  command.damping_ratio.tail<3>().maxCoeff(), k_rotational, inertia,
                                  bound, period_s));
  }
  if (has(command.fields, CommandField::kNullspace)) {
    for (Eigen::Index i = 0; i < command.nullspace_stiffness.size(); ++i) {
      const std::string joint = " of joint " + std::to_string(i + 1);
      verdicts.push_back(
          checkStiffness("nullspace_stiffness" + joint, command.nullspace_stiffness[i], "N m/rad",
                         bound.joint_inertia[i], kJointInertia, bound, period_s, rateOf(bound, i)));
      verdicts.push_back(checkDamping("nullspace_damping" + joint, command.nullspace_damping[i],
                                      "N m s/rad", bound.joint_inertia[i], kJointInertia, bound,
                                      period_s));
    }
  }
  for (Verdict& verdict : verdicts) {
    if (!verdict.accepted) {
      return std::move(verdict);
    }
  }
  return bound.drive_gains && bound.joint_lever_sq.size() == bound.joint_inertia.size()
             ? checkDriveGains(command, bound, period_s)
             : Verdict{};
}

Verdict checkRenderable(const JointCommand& command, const GainBound& bound, double period_s) {
  if (!bound.enabled() || !(period_s > 0.0)) {
    return {};
  }
  for (Eigen::Index i = 0; i < bound.joint_inertia.size(); ++i) {
    const std::string joint = " of joint " + std::to_string(i + 1);
    if (has(command.fields, CommandField::kStiffness) && i < command.stiffness.size()) {
      Verdict verdict =
          checkStiffness("stiffness" + joint, command.stiffness[i], "N m/rad",
                         bound.joint_inertia[i], kJointInertia, bound, period_s, rateOf(bound, i));
      if (!verdict.accepted) {
        return verdict;
      }
    }
    if (has(command.fields, CommandField::kDamping) && i < command.damping.size()) {
      Verdict verdict = checkDamping("damping" + joint, command.damping[i], "N m s/rad",
                                     bound.joint_inertia[i], kJointInertia, bound, period_s);
      if (!verdict.accepted) {
        return verdict;
      }
    }
  }
  return {};
}

}  // namespace comply::pipeline
