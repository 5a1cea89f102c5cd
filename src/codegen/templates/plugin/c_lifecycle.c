/* The law's state and lifecycle: create() (where plugin_parameters arrive), destroy() and
 * activate(). */

typedef struct my_law {
  int32_t dof;
} my_law;

static void* create(int32_t dof, const comply_parameters* parameters, char* error,
                    size_t error_capacity) {
  my_law* law;
  (void)parameters;
  /* step() indexes the fixed-capacity arrays with dof, so refuse what they cannot hold. */
  if (dof < 1 || dof > COMPLY_MAX_DOF) {
    snprintf(error, error_capacity, "dof %d outside 1..%d", (int)dof, COMPLY_MAX_DOF);
    return NULL;
  }
  law = (my_law*)malloc(sizeof *law);
  if (law == NULL) {
    snprintf(error, error_capacity, "out of memory");
    return NULL;
  }
  law->dof = dof;
  return law;
}

static void destroy(void* instance) {
  free(instance);
}

static comply_status activate(void* instance, const comply_input* input) {
  (void)instance;
  (void)input;
  return COMPLY_OK;
}
