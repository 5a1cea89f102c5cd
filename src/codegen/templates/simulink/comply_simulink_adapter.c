/*
 * comply plugin adapter for C code that Embedded Coder generates from a Simulink model NAME
 * (written by `comply codegen simulink`; built by the CMakeLists.txt next to it).
 *
 * It expects the configuration comply_new_model.m sets up: ERT target, reusable function code
 * interface, root-level I/O passed as structures, so that the generated NAME.h declares
 *   RT_MODEL_NAME_T, ExtU_NAME_T {comply_input input; comply_*_command command;},
 *   ExtY_NAME_T {real_T torque[COMPLY_MAX_DOF];}, optionally DW_NAME_T (states) and P_NAME_T
 *   (tunable parameters, default values in NAME_P), and
 *   NAME_initialize(M, U, Y), NAME_step(M, U, Y), NAME_terminate(M).
 * The buses are imported from comply's abi.h (comply_buses.m), so U holds comply's structs and
 * the copies below are plain struct assignments. comply_model_config.h, written by CMake, names the
 * model, its command kind, the model quantities it needs and the parameters the controller YAML
 * may set (plugin_parameters: {name: value or [values]}).
 */
#include <stddef.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "comply/plugin/abi.h"
#include "comply_model_config.h"

#define COMPLY_CAT_(a, b) a##b
#define COMPLY_CAT(a, b) COMPLY_CAT_(a, b)
#define COMPLY_MODEL_FN(suffix) COMPLY_CAT(COMPLY_MODEL, suffix)
#define COMPLY_MODEL_TYPE(prefix) COMPLY_CAT(COMPLY_CAT(prefix, COMPLY_MODEL), _T)

typedef COMPLY_MODEL_TYPE(RT_MODEL_) model_t;
typedef COMPLY_MODEL_TYPE(ExtU_) inputs_t;
typedef COMPLY_MODEL_TYPE(ExtY_) outputs_t;

typedef struct instance {
  model_t model;
#if COMPLY_MODEL_HAS_DWORK
  COMPLY_MODEL_TYPE(DW_) dwork;
#endif
#if COMPLY_MODEL_HAS_PARAMS
  COMPLY_MODEL_TYPE(P_) params;
#endif
  inputs_t inputs;
  outputs_t outputs;
  int32_t dof;
} instance;

typedef struct parameter_slot {
  const char* name;
  size_t offset; /* into P_NAME_T */
  size_t count;  /* real_T values */
} parameter_slot;

#if COMPLY_MODEL_HAS_PARAMS
#define COMPLY_PARAMETER(name)                   \
  {#name, offsetof(COMPLY_MODEL_TYPE(P_), name), \
   sizeof(((COMPLY_MODEL_TYPE(P_)*)0)->name) / sizeof(real_T)},
static const parameter_slot parameter_slots[] = {COMPLY_MODEL_PARAMETERS{NULL, 0, 0}};
#else
static const parameter_slot parameter_slots[] = {{NULL, 0, 0}};
#endif

static void write_error(char* error, size_t capacity, const char* text, const char* name) {
  if (error != NULL && capacity > 0) {
    snprintf(error, capacity, text, name);
  }
}

/* Copies one plugin_parameters entry into the instance's parameters; 0 on success. */
static int set_parameter(instance* law, const comply_parameter* item, char* error,
                         size_t capacity) {
  const parameter_slot* slot;
  for (slot = parameter_slots; slot->name != NULL; ++slot) {
    if (strcmp(slot->name, item->name) == 0) {
      break;
    }
  }
  if (slot->name == NULL) {
    write_error(error, capacity, "parameter '%s' is not a tunable parameter of the model",
                item->name);
    return 1;
  }
  if (item->values == NULL || (size_t)item->count != slot->count) {
    write_error(error, capacity, "parameter '%s' has the wrong number of values", item->name);
    return 1;
  }
#if COMPLY_MODEL_HAS_PARAMS
  memcpy((char*)&law->params + slot->offset, item->values, slot->count * sizeof(real_T));
#else
  (void)law;
#endif
  return 0;
}

static void* create(int32_t dof, const comply_parameters* parameters, char* error,
                    size_t error_capacity) {
  instance* law;
  int32_t i;
  if (dof < 1 || dof > COMPLY_MAX_DOF) {
    write_error(error, error_capacity, "dof outside 1..COMPLY_MAX_DOF%s", "");
    return NULL;
  }
  law = (instance*)calloc(1, sizeof *law);
  if (law == NULL) {
    write_error(error, error_capacity, "out of memory%s", "");
    return NULL;
  }
  law->dof = dof;
#if COMPLY_MODEL_HAS_PARAMS
  law->params = COMPLY_CAT(COMPLY_MODEL, _P); /* the model's defaults, then the YAML's values */
  law->model.defaultParam = &law->params;
#endif
#if COMPLY_MODEL_HAS_DWORK
  law->model.dwork = &law->dwork;
#endif
  for (i = 0; parameters != NULL && i < parameters->count; ++i) {
    if (set_parameter(law, &parameters->items[i], error, error_capacity) != 0) {
      free(law);
      return NULL;
    }
  }
  COMPLY_MODEL_FN(_initialize)(&law->model, &law->inputs, &law->outputs);
  return law;
}

static void destroy(void* instance_pointer) {
  instance* law = (instance*)instance_pointer;
  COMPLY_MODEL_FN(_terminate)(&law->model);
  free(law);
}

static uint32_t required_quantities(const void* instance_pointer) {
  (void)instance_pointer;
  return COMPLY_MODEL_REQUIRED_QUANTITIES;
}

/* Re-initialising resets the model's states, as a fresh activation of any other law does. */
static comply_status activate(void* instance_pointer, const comply_input* input) {
  instance* law = (instance*)instance_pointer;
  (void)input;
  COMPLY_MODEL_FN(_initialize)(&law->model, &law->inputs, &law->outputs);
  return COMPLY_OK;
}

static comply_status step(void* instance_pointer, const comply_input* input, const void* command,
                          comply_output* output) {
  instance* law = (instance*)instance_pointer;
  int32_t i;
  law->inputs.input = *input;
  law->inputs.command = *(const COMPLY_MODEL_COMMAND*)command;
  COMPLY_MODEL_FN(_step)(&law->model, &law->inputs, &law->outputs);
  if (law->model.errorStatus != NULL) {
    snprintf(output->message, COMPLY_MESSAGE_CAPACITY, "%s", law->model.errorStatus);
    return COMPLY_ERROR;
  }
  for (i = 0; i < law->dof; ++i) {
    output->torque[i] = law->outputs.torque[i];
  }
  return COMPLY_OK;
}

COMPLY_EXPORT_C_PLUGIN(COMPLY_MODEL_NAME, COMPLY_MODEL_COMMAND_KIND)
