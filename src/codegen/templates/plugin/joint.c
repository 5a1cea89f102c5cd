/*
 * my_law: joint impedance in C99, tau_i = K_i (q_ref,i - q_i) + D_i (dq_ref,i - dq_i) + tau_ff,i.
 *
 * A starting point written by `comply plugin new`: gains, targets and feedforward come from the
 * command, which the wrapper hands over complete every cycle (its initial gains until a sender
 * sets others). Change step() into your law; create() is where plugin_parameters arrive.
 */
#include <stdio.h>
#include <stdlib.h>

#include "comply/plugin/abi.h"

/* COMPLY_TEMPLATE_C_LIFECYCLE */

static uint32_t required_quantities(const void* instance) {
  (void)instance;
  return 0; /* q and dq are always there; this law needs no model quantity. */
}

static comply_status step(void* instance, const comply_input* input, const void* command,
                          comply_output* output) {
  const my_law* law = (const my_law*)instance;
  const comply_joint_command* target = (const comply_joint_command*)command;
  const double* q = input->position;
  const double* dq = input->velocity;
  const double* q_ref = target->position;
  const double* dq_ref = target->velocity;
  int32_t i;
  for (i = 0; i < law->dof; ++i) {
    const double spring = target->stiffness[i] * (q_ref[i] - q[i]);
    const double damper = target->damping[i] * (dq_ref[i] - dq[i]);
    output->torque[i] = spring + damper + target->torque_feedforward[i];
  }
  return COMPLY_OK;
}

COMPLY_EXPORT_C_PLUGIN("my_law", COMPLY_COMMAND_JOINT)
