/*
 * Loads the built plugin as comply does (dlopen, comply_plugin_entry) and checks its table and
 * its law on two inputs: no error must give zero torque, a displaced target the spring's torque.
 * Usage: plugin_test PATH_TO_PLUGIN.so (CTest passes the built library). EXPECTED_KIND comes from
 * CMakeLists.txt.
 */
#include <dlfcn.h>
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "comply/plugin/abi.h"

#define DOF 7

static int failures = 0;

static void expect_near(const char* what, int joint, double actual, double expected) {
  if (fabs(actual - expected) > 1e-9 * (1.0 + fabs(expected))) {
    printf("FAIL %s: torque[%d] = %g, expected %g\n", what, joint, actual, expected);
    ++failures;
  }
}

/* One step of `instance`, comparing every joint's torque with `expected`. */
static void expect_torque(const comply_plugin_api* api, void* instance, const comply_input* input,
                          const void* command, const double* expected, const char* what) {
  comply_output output;
  int i;
  memset(&output, 0, sizeof output);
  if (api->step(instance, input, command, &output) != COMPLY_OK) {
    printf("FAIL %s: step failed: %s\n", what, output.message);
    ++failures;
    return;
  }
  for (i = 0; i < DOF; ++i) {
    expect_near(what, i, output.torque[i], expected[i]);
  }
}

/* K = 100 N m/rad on every joint: 0.1 rad short on joint 0 must pull it with +10 N m. */
static void check_joint(const comply_plugin_api* api, void* instance, comply_input* input) {
  comply_joint_command command;
  double expected[DOF] = {0};
  int i;
  memset(&command, 0, sizeof command);
  command.dof = DOF;
  for (i = 0; i < DOF; ++i) {
    input->position[i] = command.position[i] = 0.1 * i;
    command.stiffness[i] = 100.0;
    command.damping[i] = 10.0;
  }
  expect_torque(api, instance, input, &command, expected, "zero error");
  command.position[0] += 0.1;
  expected[0] = 10.0;
  expect_torque(api, instance, input, &command, expected, "joint 0 displaced");
}

/* J = [I 0] and K = 1000 N/m: a target 1 cm further along x must push joint 0 with +10 N m. */
static void check_cartesian(const comply_plugin_api* api, void* instance, comply_input* input) {
  static const double down[4] = {1.0, 0.0, 0.0, 0.0}; /* x y z w: tool pointing down */
  comply_cartesian_command command;
  double expected[DOF] = {0};
  int i;
  memset(&command, 0, sizeof command);
  command.dof = DOF;
  command.damping_mode = COMPLY_DAMPING_ABSOLUTE;
  for (i = 0; i < 6; ++i) {
    input->jacobian[i * 6 + i] = 1.0;
  }
  for (i = 0; i < 3; ++i) {
    input->tcp_position[i] = command.position[i] = 0.3 + 0.1 * i;
    command.stiffness_translational[i * 4] = 1000.0;
    command.stiffness_rotational[i * 4] = 30.0;
    command.damping_translational[i * 4] = 40.0;
    command.damping_rotational[i * 4] = 3.0;
  }
  memcpy(input->tcp_orientation, down, sizeof down);
  memcpy(command.orientation, down, sizeof down);
  expect_torque(api, instance, input, &command, expected, "zero error");
  command.position[0] += 0.01;
  expected[0] = 1000.0 * (command.position[0] - input->tcp_position[0]);
  expect_torque(api, instance, input, &command, expected, "TCP displaced along x");
}

static void check_law(const comply_plugin_api* api) {
  static comply_input input; /* static: zero-initialised and off the stack (it is large) */
  comply_parameters no_parameters = {NULL, 0};
  char error[256] = "";
  void* instance = api->create(DOF, &no_parameters, error, sizeof error);
  if (instance == NULL) {
    printf("FAIL create(%d): %s\n", DOF, error);
    ++failures;
    return;
  }
  input.dof = DOF;
  input.available = api->required_quantities(instance);
  input.period_s = 0.001;
  if (api->activate(instance, &input) != COMPLY_OK) {
    printf("FAIL activate\n");
    ++failures;
  } else if (api->command_kind == COMPLY_COMMAND_JOINT) {
    check_joint(api, instance, &input);
  } else {
    check_cartesian(api, instance, &input);
  }
  api->destroy(instance);
}

int main(int argc, char** argv) {
  void* library;
  comply_plugin_entry_fn entry;
  const comply_plugin_api* api;
  if (argc != 2) {
    printf("usage: %s PLUGIN.so\n", argv[0]);
    return 2;
  }
  library = dlopen(argv[1], RTLD_NOW | RTLD_LOCAL);
  if (library == NULL) {
    printf("FAIL dlopen: %s\n", dlerror());
    return 1;
  }
  *(void**)(&entry) = dlsym(library, COMPLY_ENTRY_SYMBOL);
  if (entry == NULL) {
    printf("FAIL no %s in %s\n", COMPLY_ENTRY_SYMBOL, argv[1]);
    return 1;
  }
  api = entry();
  if (api->abi_version != COMPLY_ABI_VERSION || api->command_kind != EXPECTED_KIND) {
    printf("FAIL abi_version %u (expected %d), command_kind %d (expected %d)\n",
           (unsigned)api->abi_version, COMPLY_ABI_VERSION, (int)api->command_kind, EXPECTED_KIND);
    return 1;
  }
  check_law(api);
  printf("%s: %s\n", api->name, failures == 0 ? "all checks passed" : "FAILED");
  dlclose(library);
  return failures == 0 ? 0 : 1;
}
