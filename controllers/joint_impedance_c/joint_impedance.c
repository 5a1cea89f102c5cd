/*
 * Joint impedance in plain C99 against abi.h alone: tau_i = K_i (q_d,i - q_i) + D_i (dq_d,i - dq_i)
 * + tau_ff,i. It mirrors controllers/joint_impedance (parameters, error texts, order of operations)
 * and is tested to give bit-identical torques, so it doubles as the reference for writing a plugin
 * without the C++ SDK.
 */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "comply/plugin/abi.h"

typedef struct joint_impedance {
  int32_t dof;
  double max_stiffness;
} joint_impedance;

static void write_error(char* error, size_t capacity, const char* text) {
  if (error != NULL && capacity > 0) {
    snprintf(error, capacity, "%s", text);
  }
}

static const comply_parameter* find_parameter(const comply_parameters* parameters,
                                              const char* name) {
  int32_t i;
  if (parameters == NULL) {
    return NULL;
  }
  for (i = 0; i < parameters->count; ++i) {
    const comply_parameter* item = &parameters->items[i];
    if (item->name != NULL && strcmp(item->name, name) == 0) {
      return item;
    }
  }
  return NULL;
}

static void* create(int32_t dof, const comply_parameters* parameters, char* error,
                    size_t error_capacity) {
  const comply_parameter* max_stiffness = find_parameter(parameters, "max_stiffness");
  joint_impedance* law;
  if (dof < 1 || dof > COMPLY_MAX_DOF) {
    if (error != NULL && error_capacity > 0) {
      snprintf(error, error_capacity, "dof %d outside 1..%d", (int)dof, COMPLY_MAX_DOF);
    }
    return NULL;
  }
  law = (joint_impedance*)malloc(sizeof *law);
  if (law == NULL) {
    write_error(error, error_capacity, "out of memory");
    return NULL;
  }
  law->dof = dof;
  law->max_stiffness = INFINITY;
  if (max_stiffness != NULL) {
    if (max_stiffness->values == NULL || max_stiffness->count != 1) {
      write_error(error, error_capacity, "parameter 'max_stiffness' must be one number");
      free(law);
      return NULL;
    }
    law->max_stiffness = max_stiffness->values[0];
  }
  /* Written so that NaN is refused too: a NaN limit would silently disable the check. */
  if (!(law->max_stiffness >= 0.0)) {
    write_error(error, error_capacity, "parameter 'max_stiffness' must be >= 0");
    free(law);
    return NULL;
  }
  return law;
}

static void destroy(void* instance) {
  free(instance);
}

static uint32_t required_quantities(const void* instance) {
  (void)instance;
  return 0;
}

static comply_status activate(void* instance, const comply_input* input) {
  (void)instance;
  (void)input;
  return COMPLY_OK;
}

static comply_status step(void* instance, const comply_input* input, const void* command,
                          comply_output* output) {
  const joint_impedance* law = (const joint_impedance*)instance;
  const comply_joint_command* target = (const comply_joint_command*)command;
  int32_t i;
  for (i = 0; i < law->dof; ++i) {
    if (target->stiffness[i] > law->max_stiffness) {
      snprintf(output->message, COMPLY_MESSAGE_CAPACITY,
               "joint %d: stiffness %g exceeds max_stiffness %g", (int)i, target->stiffness[i],
               law->max_stiffness);
      return COMPLY_ERROR;
    }
  }
  for (i = 0; i < law->dof; ++i) {
    const double spring = target->stiffness[i] * (target->position[i] - input->position[i]);
    const double damper = target->damping[i] * (target->velocity[i] - input->velocity[i]);
    output->torque[i] = spring + damper + target->torque_feedforward[i];
  }
  return COMPLY_OK;
}

COMPLY_EXPORT_C_PLUGIN("joint_impedance_c", COMPLY_COMMAND_JOINT)
