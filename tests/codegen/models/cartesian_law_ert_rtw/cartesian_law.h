/*
 * Written by hand in Embedded Coder's conventions (reusable function, root-level I/O as
 * structures, imported buses) for a model `cartesian_law`: the Cartesian impedance law of the
 * plugin cartesian_impedance in absolute damping mode, task frame relative to the base,
 *   e = [p - p_d; -phi], phi = R 2 log(eta^-1 eta_d),  e_v = J dq - v_d,
 *   K = R_t K_t R_t^T, D = R_t D_t R_t^T (both blocks),
 *   tau = J^T (-K e - D e_v + w_ff) + N^T tau_ns + tau_ff,
 *   N^T tau_ns = tau_ns - J^T (J J^T + lambda^2 I)^-1 J tau_ns,
 *   tau_ns = K_ns (q_ns - q) - D_ns dq,
 * with lambda the tunable nullspace_dls_damping. Ratio-mode damping sets errorStatus.
 */
#ifndef RTW_HEADER_cartesian_law_h_
#define RTW_HEADER_cartesian_law_h_
#include "cartesian_law_types.h"
#include "rtwtypes.h"

typedef struct {
  comply_input input;               /* '<Root>/input' */
  comply_cartesian_command command; /* '<Root>/command' */
} ExtU_cartesian_law_T;

typedef struct {
  real_T torque[12]; /* '<Root>/torque' */
} ExtY_cartesian_law_T;

struct P_cartesian_law_T_ {
  real_T nullspace_dls_damping; /* Variable: nullspace_dls_damping */
};

struct tag_RTM_cartesian_law_T {
  const char_T* volatile errorStatus;
  P_cartesian_law_T* defaultParam;
};

extern P_cartesian_law_T cartesian_law_P;

extern void cartesian_law_initialize(RT_MODEL_cartesian_law_T* const cartesian_law_M,
                                     ExtU_cartesian_law_T* cartesian_law_U,
                                     ExtY_cartesian_law_T* cartesian_law_Y);
extern void cartesian_law_step(RT_MODEL_cartesian_law_T* const cartesian_law_M,
                               ExtU_cartesian_law_T* cartesian_law_U,
                               ExtY_cartesian_law_T* cartesian_law_Y);
extern void cartesian_law_terminate(RT_MODEL_cartesian_law_T* const cartesian_law_M);
#endif
