#pragma once
// Errors of the simulation module: scene files, MuJoCo load errors, rendering setup.

#include <stdexcept>

namespace comply::sim {

class SimError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

}  // namespace comply::sim
