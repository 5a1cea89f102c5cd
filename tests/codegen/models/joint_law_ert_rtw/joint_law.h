/*
 * Written by hand in Embedded Coder's conventions (reusable function, root-level I/O as
 * structures, imported buses) for a model `joint_law`: joint impedance with a tunable
 * feedforward gain, tau = K (q_d - q) + D (dq_d - dq) + feedforward_gain tau_ff.
 */
#ifndef RTW_HEADER_joint_law_h_
#define RTW_HEADER_joint_law_h_
#include "joint_law_types.h"
#include "rtwtypes.h"

typedef struct {
  uint32_T steps; /* '<S1>/Counter' */
} DW_joint_law_T;

typedef struct {
  comply_input input;           /* '<Root>/input' */
  comply_joint_command command; /* '<Root>/command' */
} ExtU_joint_law_T;

typedef struct {
  real_T torque[12]; /* '<Root>/torque' */
} ExtY_joint_law_T;

struct P_joint_law_T_ {
  real_T feedforward_gain; /* Variable: feedforward_gain */
};

struct tag_RTM_joint_law_T {
  const char_T* volatile errorStatus;
  P_joint_law_T* defaultParam;
  DW_joint_law_T* dwork;
};

extern P_joint_law_T joint_law_P;

extern void joint_law_initialize(RT_MODEL_joint_law_T* const joint_law_M,
                                 ExtU_joint_law_T* joint_law_U, ExtY_joint_law_T* joint_law_Y);
extern void joint_law_step(RT_MODEL_joint_law_T* const joint_law_M, ExtU_joint_law_T* joint_law_U,
                           ExtY_joint_law_T* joint_law_Y);
extern void joint_law_terminate(RT_MODEL_joint_law_T* const joint_law_M);
#endif
