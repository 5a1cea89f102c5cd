#pragma once
// Fixed capacities shared by every module. The real-time path never allocates, so every per-joint
// quantity lives in storage sized for the largest arm comply supports.

#include <Eigen/Core>

namespace comply {

/// Largest number of controlled joints of one controller (a 7-DOF arm on a 3-DOF base + 2 spare).
inline constexpr int kMaxDof = 12;

/// Longest header.frame_id a command, chunk or request may carry [bytes]: a frame's name, never
/// data. A transport refuses a longer one where it reads the sample (reason too_large), so that
/// no sender's megabytes travel further than that read.
inline constexpr int kMaxFrameIdBytes = 256;

/// Per-joint vector with run-time size <= kMaxDof and inline storage (never touches the heap).
using JointVector = Eigen::Matrix<double, Eigen::Dynamic, 1, Eigen::ColMajor, kMaxDof, 1>;

/// Joint-space square matrix (e.g. the mass matrix) with inline storage.
using JointMatrix =
    Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::ColMajor, kMaxDof, kMaxDof>;

/// Geometric Jacobian, 6 x dof: rows 0-2 linear velocity, rows 3-5 angular velocity.
using Jacobian = Eigen::Matrix<double, 6, Eigen::Dynamic, Eigen::ColMajor, 6, kMaxDof>;

}  // namespace comply
