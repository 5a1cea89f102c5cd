/* The step function of `joint_law` in Embedded Coder's reusable-function form. */
#include "joint_law.h"

#include <string.h>

void joint_law_step(RT_MODEL_joint_law_T* const joint_law_M, ExtU_joint_law_T* joint_law_U,
                    ExtY_joint_law_T* joint_law_Y) {
  P_joint_law_T* joint_law_P_ = joint_law_M->defaultParam;
  DW_joint_law_T* joint_law_DW = joint_law_M->dwork;
  int32_T i;
  for (i = 0; i < joint_law_U->input.dof; i++) {
    joint_law_Y->torque[i] =
        (joint_law_U->command.stiffness[i] *
             (joint_law_U->command.position[i] - joint_law_U->input.position[i]) +
         joint_law_U->command.damping[i] *
             (joint_law_U->command.velocity[i] - joint_law_U->input.velocity[i])) +
        joint_law_P_->feedforward_gain * joint_law_U->command.torque_feedforward[i];
  }
  joint_law_DW->steps++;
}

void joint_law_initialize(RT_MODEL_joint_law_T* const joint_law_M, ExtU_joint_law_T* joint_law_U,
                          ExtY_joint_law_T* joint_law_Y) {
  joint_law_M->errorStatus = (const char_T*)0;
  memset(joint_law_M->dwork, 0, sizeof(DW_joint_law_T));
  memset(joint_law_U, 0, sizeof(ExtU_joint_law_T));
  memset(joint_law_Y, 0, sizeof(ExtY_joint_law_T));
}

void joint_law_terminate(RT_MODEL_joint_law_T* const joint_law_M) {
  (void)joint_law_M;
}
