#pragma once
// Joint values written into the C buses' arrays, from index 0 (a header of its own: the tests of a
// single law do not link the model).

#include <algorithm>
#include <initializer_list>

namespace comply::law_test {

/// Writes one value per joint, from joint 0, into a bus array.
inline void writeJoints(std::initializer_list<double> values, double* joints) {
  std::copy(values.begin(), values.end(), joints);
}

}  // namespace comply::law_test
