/*
 * Written by hand in Embedded Coder's conventions for a model `joint_law` built with
 * comply_new_model.m's configuration (tests/codegen/README.md says why).
 */
#ifndef RTW_HEADER_joint_law_types_h_
#define RTW_HEADER_joint_law_types_h_
#include "comply/plugin/abi.h" /* imported buses: DataScope 'Imported', HeaderFile abi.h */
#include "rtwtypes.h"

typedef struct P_joint_law_T_ P_joint_law_T;
typedef struct tag_RTM_joint_law_T RT_MODEL_joint_law_T;
#endif
