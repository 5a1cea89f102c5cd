#pragma once
// A joint vector written out in a test: joints({0.1, -0.2, 0.3}).

#include <initializer_list>

#include "comply/core/capacity.hpp"

namespace comply::pipeline {

inline JointVector joints(std::initializer_list<double> values) {
  JointVector v(static_cast<Eigen::Index>(values.size()));
  Eigen::Index i = 0;
  for (const double value : values) {
    v[i++] = value;
  }
  return v;
}

}  // namespace comply::pipeline
