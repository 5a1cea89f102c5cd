/*
 * The step function of `cartesian_law` in Embedded Coder's reusable-function form. Its arithmetic
 * follows controllers/cartesian_impedance/cartesian_impedance.cpp term by term (absolute damping,
 * task_frame_reference: base). Matrices here are row-major 3x3 and 6x6; the Jacobian is read as
 * the input bus holds it, column-major 6 x dof.
 */
#include "cartesian_law.h"

#include <math.h>
#include <string.h>

#define J_(row, col) (U->input.jacobian[(col)*6 + (row)])

/* R (row-major) of a quaternion x y z w, as Eigen's toRotationMatrix (no normalisation). */
static void quaternion_to_rotation(const real_T* q, real_T* R) {
  real_T tx = 2.0 * q[0];
  real_T ty = 2.0 * q[1];
  real_T tz = 2.0 * q[2];
  real_T twx = tx * q[3];
  real_T twy = ty * q[3];
  real_T twz = tz * q[3];
  real_T txx = tx * q[0];
  real_T txy = ty * q[0];
  real_T txz = tz * q[0];
  real_T tyy = ty * q[1];
  real_T tyz = tz * q[1];
  real_T tzz = tz * q[2];
  R[0] = 1.0 - (tyy + tzz);
  R[1] = txy - twz;
  R[2] = txz + twy;
  R[3] = txy + twz;
  R[4] = 1.0 - (txx + tzz);
  R[5] = tyz - twx;
  R[6] = txz - twy;
  R[7] = tyz + twx;
  R[8] = 1.0 - (txx + tyy);
}

/* phi = R_current 2 log(current^-1 desired), short way round (w >= 0), as comply's
 * orientationError; quaternions x y z w. */
static void orientation_error(const real_T* c, const real_T* d, real_T* phi) {
  real_T rel[4]; /* conj(c) * d, x y z w */
  real_T log_rel[3];
  real_T R[9];
  real_T sin_half;
  int32_T i;
  rel[3] = c[3] * d[3] - -c[0] * d[0] - -c[1] * d[1] - -c[2] * d[2];
  rel[0] = c[3] * d[0] + -c[0] * d[3] + -c[1] * d[2] - -c[2] * d[1];
  rel[1] = c[3] * d[1] + -c[1] * d[3] + -c[2] * d[0] - -c[0] * d[2];
  rel[2] = c[3] * d[2] + -c[2] * d[3] + -c[0] * d[1] - -c[1] * d[0];
  if (rel[3] < 0.0) {
    for (i = 0; i < 4; i++) {
      rel[i] = -rel[i];
    }
  }
  sin_half = sqrt(rel[0] * rel[0] + rel[1] * rel[1] + rel[2] * rel[2]);
  for (i = 0; i < 3; i++) {
    /* Small angle: log ~ v / w, keeping the derivative. */
    log_rel[i] = sin_half < 1e-12 ? 2.0 * rel[i] / rel[3]
                                  : 2.0 * atan2(sin_half, rel[3]) * rel[i] / sin_half;
  }
  quaternion_to_rotation(c, R);
  for (i = 0; i < 3; i++) {
    phi[i] = R[3 * i] * log_rel[0] + R[3 * i + 1] * log_rel[1] + R[3 * i + 2] * log_rel[2];
  }
}

/* Block (row-major 3x3 from the command) into rows/columns `at` of the 6x6 G, turned into the
 * base frame, R B R^T, when the task frame is not the base frame. */
static void gain_block(const real_T* B, const real_T* R, boolean_T rotated, int32_T at, real_T* G) {
  real_T RB[9];
  int32_T i;
  int32_T j;
  for (i = 0; i < 3; i++) {
    for (j = 0; j < 3; j++) {
      RB[3 * i + j] = R[3 * i] * B[j] + R[3 * i + 1] * B[3 + j] + R[3 * i + 2] * B[6 + j];
    }
  }
  for (i = 0; i < 3; i++) {
    for (j = 0; j < 3; j++) {
      G[6 * (at + i) + at + j] = rotated ? RB[3 * i] * R[3 * j] + RB[3 * i + 1] * R[3 * j + 1] +
                                               RB[3 * i + 2] * R[3 * j + 2]
                                         : B[3 * i + j];
    }
  }
}

/* x = A^-1 b for a symmetric positive definite 6x6 A by unblocked L D L^T, as the reference's
 * solvePositiveDefinite; 0 when a pivot is not positive. */
static boolean_T solve_ldlt(const real_T* A, const real_T* b, real_T* x) {
  real_T L[36] = {0.0}; /* unit lower triangular, diagonal not stored */
  real_T S[36] = {0.0}; /* L_ik d_k */
  real_T recip[6];
  real_T z[6];
  real_T value;
  int32_T i;
  int32_T j;
  int32_T k;
  for (j = 0; j < 6; j++) {
    value = A[6 * j + j];
    for (k = 0; k < j; k++) {
      value -= L[6 * j + k] * S[6 * j + k];
    }
    if (!(value > 0.0)) {
      return 0;
    }
    recip[j] = 1.0 / value;
    for (i = j + 1; i < 6; i++) {
      value = A[6 * i + j];
      for (k = 0; k < j; k++) {
        value -= S[6 * i + k] * L[6 * j + k];
      }
      S[6 * i + j] = value;
      L[6 * i + j] = value * recip[j];
    }
  }
  for (i = 0; i < 6; i++) {
    value = b[i];
    for (k = 0; k < i; k++) {
      value -= L[6 * i + k] * z[k];
    }
    z[i] = value;
  }
  for (i = 5; i >= 0; i--) {
    value = z[i] * recip[i];
    for (k = i + 1; k < 6; k++) {
      value -= L[6 * k + i] * x[k];
    }
    x[i] = value;
  }
  return 1;
}

void cartesian_law_step(RT_MODEL_cartesian_law_T* const cartesian_law_M,
                        ExtU_cartesian_law_T* cartesian_law_U,
                        ExtY_cartesian_law_T* cartesian_law_Y) {
  const ExtU_cartesian_law_T* U = cartesian_law_U;
  const comply_cartesian_command* cmd = &U->command;
  real_T lambda = cartesian_law_M->defaultParam->nullspace_dls_damping;
  int32_T n = U->input.dof;
  real_T e[6];                                                 /* pose error */
  real_T e_v[6];                                               /* twist error */
  real_T R[9] = {1.0, 0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 1.0}; /* task frame in base */
  real_T K[36] = {0.0};
  real_T D[36] = {0.0};
  real_T w[6]; /* wrench */
  real_T tau_ns[12];
  real_T A[36]; /* J J^T + lambda^2 I */
  real_T b[6];  /* J tau_ns */
  real_T x[6];
  real_T norm;
  real_T q[4];
  boolean_T rotated;
  int32_T i;
  int32_T j;
  int32_T k;
  cartesian_law_M->errorStatus = (const char_T*)0;
  if (cmd->damping_mode != COMPLY_DAMPING_ABSOLUTE) {
    cartesian_law_M->errorStatus = "cartesian_law supports damping_mode: absolute only";
    return;
  }

  /* Pose and twist errors in the base frame. */
  for (i = 0; i < 3; i++) {
    e[i] = U->input.tcp_position[i] - cmd->position[i];
  }
  orientation_error(U->input.tcp_orientation, cmd->orientation, &e[3]);
  for (i = 3; i < 6; i++) {
    e[i] = -e[i];
  }
  for (i = 0; i < 6; i++) {
    e_v[i] = 0.0;
    for (k = 0; k < n; k++) {
      e_v[i] += J_(i, k) * U->input.velocity[k];
    }
    e_v[i] -= cmd->twist[i];
  }

  /* Gains from the task frame (normalised quaternion) to the base frame. */
  rotated = cmd->task_frame[0] * cmd->task_frame[0] + cmd->task_frame[1] * cmd->task_frame[1] +
                cmd->task_frame[2] * cmd->task_frame[2] !=
            0.0;
  if (rotated) {
    norm =
        sqrt((cmd->task_frame[0] * cmd->task_frame[0] + cmd->task_frame[2] * cmd->task_frame[2]) +
             (cmd->task_frame[1] * cmd->task_frame[1] + cmd->task_frame[3] * cmd->task_frame[3]));
    for (i = 0; i < 4; i++) {
      q[i] = cmd->task_frame[i] / norm;
    }
    quaternion_to_rotation(q, R);
  }
  gain_block(cmd->stiffness_translational, R, rotated, 0, K);
  gain_block(cmd->stiffness_rotational, R, rotated, 3, K);
  gain_block(cmd->damping_translational, R, rotated, 0, D);
  gain_block(cmd->damping_rotational, R, rotated, 3, D);

  /* w = -K e - D e_v + w_ff; tau = J^T w. */
  for (i = 0; i < 6; i++) {
    real_T ke = 0.0;
    real_T de = 0.0;
    for (j = 0; j < 6; j++) {
      ke += K[6 * i + j] * e[j];
      de += D[6 * i + j] * e_v[j];
    }
    w[i] = -ke - de + cmd->wrench_feedforward[i];
  }

  /* Nullspace: tau_ns - J^T (J J^T + lambda^2 I)^-1 J tau_ns. */
  for (k = 0; k < n; k++) {
    tau_ns[k] = cmd->nullspace_stiffness[k] * (cmd->nullspace_position[k] - U->input.position[k]) -
                cmd->nullspace_damping[k] * U->input.velocity[k];
  }
  for (i = 0; i < 6; i++) {
    b[i] = 0.0;
    for (k = 0; k < n; k++) {
      b[i] += J_(i, k) * tau_ns[k];
    }
    for (j = 0; j < 6; j++) {
      A[6 * i + j] = 0.0;
      for (k = 0; k < n; k++) {
        A[6 * i + j] += J_(i, k) * J_(j, k);
      }
      if (i == j) {
        A[6 * i + j] += lambda * lambda;
      }
    }
  }
  if (!solve_ldlt(A, b, x)) {
    /* The reference falls back to an LDLT least-squares solve here (lambda 0 at a singularity). */
    cartesian_law_M->errorStatus = "J J^T + lambda^2 I not positive definite";
    return;
  }

  for (k = 0; k < n; k++) {
    real_T task = 0.0;
    real_T projected = 0.0;
    for (i = 0; i < 6; i++) {
      task += J_(i, k) * w[i];
      projected += J_(i, k) * x[i];
    }
    cartesian_law_Y->torque[k] = task + (tau_ns[k] - projected) + cmd->torque_feedforward[k];
  }
}

void cartesian_law_initialize(RT_MODEL_cartesian_law_T* const cartesian_law_M,
                              ExtU_cartesian_law_T* cartesian_law_U,
                              ExtY_cartesian_law_T* cartesian_law_Y) {
  cartesian_law_M->errorStatus = (const char_T*)0;
  memset(cartesian_law_U, 0, sizeof(ExtU_cartesian_law_T));
  memset(cartesian_law_Y, 0, sizeof(ExtY_cartesian_law_T));
}

void cartesian_law_terminate(RT_MODEL_cartesian_law_T* const cartesian_law_M) {
  (void)cartesian_law_M;
}
