#pragma once
// Read-only C++ view of the parameters a plugin receives at creation.

#include <cstdio>
#include <span>
#include <stdexcept>
#include <string>
#include <string_view>

#include "comply/plugin/abi.h"

namespace comply::plugin {

/// Thrown by Parameters accessors; the SDK turns it into create()'s error text.
class ParameterError : public std::invalid_argument {
 public:
  using std::invalid_argument::invalid_argument;
};

/// Throws ParameterError unless 1 <= dof <= COMPLY_MAX_DOF: step() indexes the ABI's
/// fixed-capacity arrays with it. (snprintf rather than std::to_string: the latter leaves a
/// GNU-unique symbol in the library, and glibc never unloads a library that has one, which would
/// defeat reloading the plugin.)
inline void checkDof(int dof) {
  if (dof < 1 || dof > COMPLY_MAX_DOF) {
    char message[64];
    std::snprintf(message, sizeof message, "dof %d outside 1..%d", dof, COMPLY_MAX_DOF);
    throw ParameterError(message);
  }
}

class Parameters {
 public:
  explicit Parameters(const comply_parameters* parameters) : parameters_(parameters) {}

  [[nodiscard]] bool has(std::string_view name) const { return find(name) != nullptr; }

  /// A single number; `fallback` when absent. Throws when present but not one number.
  [[nodiscard]] double number(std::string_view name, double fallback) const;

  /// A list of numbers of exactly `expected_count` entries.
  /// Empty span when absent. Throws on a count mismatch or a string value.
  [[nodiscard]] std::span<const double> numbers(std::string_view name, int expected_count) const;

  /// A string; `fallback` when absent.
  [[nodiscard]] std::string text(std::string_view name, std::string_view fallback) const;

 private:
  [[nodiscard]] const comply_parameter* find(std::string_view name) const;
  const comply_parameters* parameters_;
};

}  // namespace comply::plugin
