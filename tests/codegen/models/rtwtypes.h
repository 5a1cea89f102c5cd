/*
 * Stand-in for Embedded Coder's rtwtypes.h (the subset the hand-written models use), so the
 * model sources compile exactly as generated code would, without MATLAB. One for both models, as
 * Embedded Coder's shared utilities folder holds it; the test puts a copy into each model's code
 * folder, where the adapter's CMakeLists.txt looks for it.
 */
#ifndef RTWTYPES_H
#define RTWTYPES_H
#include <stdint.h>
typedef double real_T;
typedef int32_t int32_T;
typedef uint32_t uint32_T;
typedef unsigned char boolean_T;
typedef char char_T;
#endif
