#pragma once
// Field validation, generic over a schema (see generic.hpp): sizes, finiteness and the table's
// constraints, for the groups a command sets. Include only from .cpp files and tests.

#include <limits>
#include <sstream>
#include <string>

#include "comply/core/gains.hpp"
#include "comply/core/number_text.hpp"
#include "comply/schema/generic.hpp"

namespace comply::schema::generic {

template <FieldKind K, typename Value>
bool allFinite(const Value& value) {
  if constexpr (K == FieldKind::kQuaternion) {
    return value.coeffs().allFinite();
  } else if constexpr (K == FieldKind::kEnum) {
    return true;
  } else {
    return value.allFinite();
  }
}

/// Renormalises small drift in place; false when the norm is too far from 1 (or not finite).
inline bool normaliseQuaternion(Eigen::Quaterniond& q, double tolerance) {
  const double norm = q.norm();
  if (!(std::abs(norm - 1.0) <= tolerance)) {
    return false;
  }
  q.coeffs() /= norm;
  return true;
}

/// A field's largest entry against `limit`, the gain or value limit of its unit.
template <typename Value>
CheckResult checkEntryLimit(const Value& value, const std::string& field, std::string_view unit,
                            double limit, Violation violation) {
  if (value.size() == 0) {
    return {};
  }
  const double largest = value.cwiseAbs().maxCoeff();
  if (!(largest <= limit)) {
    const NumberTexts texts = numbersApart(largest, limit);
    std::ostringstream text;
    text << field << " has an entry of " << texts.value << " " << unit << ", above the limit of "
         << texts.limit << " " << unit << " for any arm";
    return {violation, field, text.str()};
  }
  return {};
}

template <typename Value>
CheckResult checkGainLimit(const Value& value, const std::string& field, std::string_view unit) {
  return checkEntryLimit(value, field, unit, gainLimit(unit), Violation::kGainTooLarge);
}

/// The constraint of one field; a message naming it, or empty when it holds.
template <typename F>
CheckResult checkConstraint(typename F::ValueType& value, std::string_view name,
                            std::string_view unit, const CheckOptions& options) {
  const std::string field(name);
  if constexpr (F::kConstraint == Constraint::kUnitQuaternion) {
    static_assert(F::kKind == FieldKind::kQuaternion, "only quaternions have unit norm");
    const double norm = value.norm();
    if (!normaliseQuaternion(value, options.quaternion_tolerance)) {
      std::ostringstream text;
      text << field << " is not a unit quaternion (x y z w): norm " << norm;
      return {Violation::kNotUnit, field, text.str()};
    }
  } else if constexpr (F::kConstraint == Constraint::kSymmetricPsd) {
    static_assert(F::kKind == FieldKind::kBlock3, "only 3x3 blocks are checked for PSD");
    if (!isSymmetricPsd(value, options.gain_tolerance, options.gain_tolerance)) {
      return {Violation::kNotSymmetricPsd, field,
              field + " must be symmetric positive semi-definite"};
    }
    return checkGainLimit(value, field, unit);
  } else if constexpr (F::kConstraint == Constraint::kSelection) {
    static_assert(F::kKind == FieldKind::kVector6, "selections are over the six task axes");
    for (Eigen::Index i = 0; i < value.size(); ++i) {
      if (value[i] != 0.0 && value[i] != 1.0) {
        std::ostringstream text;
        text << field << " entries must be 0 or 1 (x y z rx ry rz), entry " << i << " is "
             << value[i];
        return {Violation::kNotSelection, field, text.str()};
      }
    }
  } else if constexpr (F::kConstraint == Constraint::kThreshold) {
    for (Eigen::Index i = 0; i < value.size(); ++i) {
      if (value[i] < 0.0) {
        std::ostringstream text;
        text << field << " entries must be >= 0 (0: the controller file's), entry " << i << " is "
             << value[i] << " " << unit;
        return {Violation::kNegativeThreshold, field, text.str()};
      }
    }
  } else if constexpr (F::kConstraint == Constraint::kNonNegative) {
    if (!(value.array() >= 0.0).all()) {
      return {Violation::kNegative, field, field + " must be >= 0"};
    }
    return checkGainLimit(value, field, unit);
  } else if constexpr (F::kConstraint == Constraint::kNone && F::kKind != FieldKind::kEnum &&
                       F::kKind != FieldKind::kQuaternion) {
    const double limit = valueLimit(unit);
    if (limit < std::numeric_limits<double>::infinity()) {
      return checkEntryLimit(value, field, unit, limit, Violation::kValueTooLarge);
    }
  }
  return {};
}

template <typename Schema>
CheckResult checkFields(typename Schema::Command& command, int dof, const CheckOptions& options) {
  CheckResult result;
  const CommandField set = command.fields;
  visitFields<Schema>([&](const auto& f, std::size_t) {
    using F = FieldOf<decltype(f)>;
    if constexpr (F::kKind == FieldKind::kJointVector) {
      const auto size = (command.*f.member).size();
      if (has(set, f.group) && size != dof) {
        const std::string entries = std::to_string(dof);
        result = {Violation::kWrongSize, std::string(f.name),
                  std::string(f.name) + " has " + std::to_string(size) + " entries, must have " +
                      entries + " entries: the controller has " + entries + " joints"};
      }
    }
    return result.ok();
  });
  if (!result.ok()) {
    return result;
  }
  visitFields<Schema>([&](const auto& f, std::size_t) {
    using F = FieldOf<decltype(f)>;
    if (has(set, f.group) && !allFinite<F::kKind>(command.*f.member)) {
      result = {Violation::kNonFinite, std::string(f.name),
                std::string(f.name) + " holds NaN or infinity"};
    }
    return result.ok();
  });
  if (!result.ok()) {
    return result;
  }
  visitFields<Schema>([&](const auto& f, std::size_t) {
    using F = FieldOf<decltype(f)>;
    if (has(set, f.group)) {
      result = checkConstraint<F>(command.*f.member, f.name, f.unit, options);
    }
    return result.ok();
  });
  return result;
}

}  // namespace comply::schema::generic
