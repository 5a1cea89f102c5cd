/* Tunable parameters of `joint_law` (Embedded Coder's NAME_data.c). */
#include "joint_law.h"

P_joint_law_T joint_law_P = {
    1.0 /* Variable: feedforward_gain */
};
