#pragma once
// The per-cycle model computation. Real-time safe: no allocation, no exceptions, no locks.

#include <span>

#include "comply/model/data.hpp"
#include "comply/model/model.hpp"

namespace comply::model {

enum class UpdateStatus {
  kOk,
  kSizeMismatch,     ///< q or dq does not have model.dof() entries
  kNonFinite,        ///< q or dq holds NaN or infinity; results were left untouched
};

/// Computes the requested quantities at joint positions q [rad|m] and velocities dq [rad/s|m/s],
/// both in the caller's joint order. dq is read only when Quantity::kCoriolis is requested. On
/// failure data keeps the results of the last successful update and data.computed is unchanged.
UpdateStatus update(const Model& model, Data& data, std::span<const double> q,
                    std::span<const double> dq, Quantity requested) noexcept;

}  // namespace comply::model
