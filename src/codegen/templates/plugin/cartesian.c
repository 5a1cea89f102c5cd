/*
 * my_law: Cartesian impedance in C99, a spring-damper on the TCP mapped to the joints through J^T:
 *
 *   F   = K e + D (v_ref - J dq) + w_ff,  e = [p_ref - p; rotation vector from the TCP to q_ref]
 *   tau = J^T F + tau_ff
 *
 * A starting point written by `comply plugin new`. Targets and gains come from the command, which
 * the wrapper hands over complete every cycle. To stay short it applies the gains in the base frame
 * (the command's task_frame is ignored), has no nullspace term (a redundant arm may drift in its
 * nullspace; the reference cartesian_impedance plugin adds one) and, in damping-ratio mode, damps
 * a unit mass (D_ii = 2 zeta_i sqrt(K_ii)) for lack of an inertia model.
 */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>

#include "comply/plugin/abi.h"

/* COMPLY_TEMPLATE_C_LIFECYCLE */

static uint32_t required_quantities(const void* instance) {
  (void)instance;
  return COMPLY_NEED_POSE | COMPLY_NEED_JACOBIAN;
}

/* Pose error in the base frame. The rotation part is 2 vec(q_ref q^-1) (quaternions x y z w), the
 * rotation vector for small errors; its sign picks the shorter way round. */
static void pose_error(const comply_input* input, const comply_cartesian_command* target,
                       double error[6]) {
  const double* a = target->orientation;
  const double* q = input->tcp_orientation;
  const double b[4] = {-q[0], -q[1], -q[2], q[3]};
  const double w = a[3] * b[3] - a[0] * b[0] - a[1] * b[1] - a[2] * b[2];
  const double sign = w < 0.0 ? -2.0 : 2.0;
  int i;
  for (i = 0; i < 3; ++i) {
    error[i] = target->position[i] - input->tcp_position[i];
  }
  error[3] = sign * (a[3] * b[0] + a[0] * b[3] + a[1] * b[2] - a[2] * b[1]);
  error[4] = sign * (a[3] * b[1] - a[0] * b[2] + a[1] * b[3] + a[2] * b[0]);
  error[5] = sign * (a[3] * b[2] + a[0] * b[1] - a[1] * b[0] + a[2] * b[3]);
}

/* force += K e + D e_v for one 3x3 block (row-major); ratio mode damps a unit mass per axis. */
static void spring_damper(const double* stiffness, const double* damping, const double* ratio,
                          int use_ratio, const double* e, const double* e_v, double* force) {
  int r, c;
  for (r = 0; r < 3; ++r) {
    for (c = 0; c < 3; ++c) {
      force[r] += stiffness[r * 3 + c] * e[c];
      if (!use_ratio) {
        force[r] += damping[r * 3 + c] * e_v[c];
      }
    }
    if (use_ratio) {
      force[r] += 2.0 * ratio[r] * sqrt(fabs(stiffness[r * 3 + r])) * e_v[r];
    }
  }
}

static comply_status step(void* instance, const comply_input* input, const void* command,
                          comply_output* output) {
  const my_law* law = (const my_law*)instance;
  const comply_cartesian_command* target = (const comply_cartesian_command*)command;
  const double* jacobian = input->jacobian; /* 6 x dof, column-major */
  const int use_ratio = target->damping_mode == COMPLY_DAMPING_RATIO;
  double error[6], twist_error[6], force[6];
  int32_t j;
  int r;
  pose_error(input, target, error);
  for (r = 0; r < 6; ++r) {
    twist_error[r] = target->twist[r];
    force[r] = target->wrench_feedforward[r];
  }
  for (j = 0; j < law->dof; ++j) {
    for (r = 0; r < 6; ++r) {
      twist_error[r] -= jacobian[j * 6 + r] * input->velocity[j];
    }
  }
  spring_damper(target->stiffness_translational, target->damping_translational,
                target->damping_ratio, use_ratio, error, twist_error, force);
  spring_damper(target->stiffness_rotational, target->damping_rotational, target->damping_ratio + 3,
                use_ratio, error + 3, twist_error + 3, force + 3);
  for (j = 0; j < law->dof; ++j) {
    double torque = target->torque_feedforward[j];
    for (r = 0; r < 6; ++r) {
      torque += jacobian[j * 6 + r] * force[r];
    }
    output->torque[j] = torque;
  }
  return COMPLY_OK;
}

COMPLY_EXPORT_C_PLUGIN("my_law", COMPLY_COMMAND_CARTESIAN)
