/* Tunable parameters of `cartesian_law` (Embedded Coder's NAME_data.c). */
#include "cartesian_law.h"

P_cartesian_law_T cartesian_law_P = {
    0.05 /* Variable: nullspace_dls_damping */
};
