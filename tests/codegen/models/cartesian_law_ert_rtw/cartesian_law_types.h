/*
 * Written by hand in Embedded Coder's conventions for a model `cartesian_law` built with
 * comply_new_model.m's configuration (tests/codegen/README.md says why).
 */
#ifndef RTW_HEADER_cartesian_law_types_h_
#define RTW_HEADER_cartesian_law_types_h_
#include "comply/plugin/abi.h" /* imported buses: DataScope 'Imported', HeaderFile abi.h */
#include "rtwtypes.h"

typedef struct P_cartesian_law_T_ P_cartesian_law_T;
typedef struct tag_RTM_cartesian_law_T RT_MODEL_cartesian_law_T;
#endif
