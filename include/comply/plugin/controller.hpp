#pragma once
// C++ SDK for control-law plugins. Derive from JointController or CartesianController, implement
// step(), and export the class with one line:
//
//   COMPLY_EXPORT_CONTROLLER(MyLaw, "my_law")
//
// The macro generates the C entry point and the function table of abi.h; exceptions thrown while
// configuring become create()'s error text, and step() is noexcept so nothing escapes the cycle.

#include <cstdio>
#include <exception>
#include <type_traits>

#include "comply/plugin/abi.h"
#include "comply/plugin/parameters.hpp"

namespace comply {

class Controller {
 public:
  virtual ~Controller() = default;
  /// Reads parameters; throw (e.g. plugin::ParameterError) to refuse them. Not real-time.
  virtual void configure(int dof, const plugin::Parameters& parameters) {
    (void)dof;
    (void)parameters;
  }
  /// COMPLY_NEED_* this instance needs every cycle.
  [[nodiscard]] virtual std::uint32_t requiredQuantities() const { return 0; }
  /// Called on activation with the first input (reset internal state here).
  virtual comply_status activate(const comply_input& input) noexcept {
    (void)input;
    return COMPLY_OK;
  }
};

/// A law for one command bus: implement step(), real-time, every cycle.
template <typename CommandBus>
class ControllerFor : public Controller {
 public:
  static_assert(std::is_same_v<CommandBus, comply_joint_command> ||
                    std::is_same_v<CommandBus, comply_cartesian_command>,
                "a law reads comply_joint_command or comply_cartesian_command");
  static constexpr comply_command_kind kCommandKind =
      std::is_same_v<CommandBus, comply_cartesian_command> ? COMPLY_COMMAND_CARTESIAN
                                                           : COMPLY_COMMAND_JOINT;
  using Command = CommandBus;
  virtual comply_status step(const comply_input& input, const Command& command,
                             comply_output& output) noexcept = 0;
};

class JointController : public ControllerFor<comply_joint_command> {};
class CartesianController : public ControllerFor<comply_cartesian_command> {};

namespace plugin::detail {

inline void writeError(char* buffer, size_t capacity, const char* text) {
  if (buffer != nullptr && capacity > 0) {
    std::snprintf(buffer, capacity, "%s", text);
  }
}

template <typename Law>
struct Adapter {
  static void* create(int32_t dof, const comply_parameters* parameters, char* error,
                      size_t error_capacity) {
    try {
      auto* law = new Law();
      try {
        law->configure(dof, Parameters(parameters));
      } catch (...) {
        delete law;
        throw;
      }
      return law;
    } catch (const std::exception& exception) {
      writeError(error, error_capacity, exception.what());
    } catch (...) {
      writeError(error, error_capacity, "unknown exception while configuring");
    }
    return nullptr;
  }
  static void destroy(void* instance) { delete static_cast<Law*>(instance); }
  static uint32_t requiredQuantities(const void* instance) {
    return static_cast<const Law*>(instance)->requiredQuantities();
  }
  static comply_status activate(void* instance, const comply_input* input) {
    return static_cast<Law*>(instance)->activate(*input);
  }
  static comply_status step(void* instance, const comply_input* input, const void* command,
                            comply_output* output) {
    return static_cast<Law*>(instance)->step(
        *input, *static_cast<const typename Law::Command*>(command), *output);
  }
  static const comply_plugin_api* api(const char* name) {
    static const comply_plugin_api table{
        COMPLY_ABI_VERSION, name, Law::kCommandKind, &create, &destroy, &requiredQuantities,
        &activate,          &step};
    return &table;
  }
};

}  // namespace plugin::detail
}  // namespace comply

#define COMPLY_EXPORT_CONTROLLER(LawClass, plugin_name)                                           \
  extern "C" __attribute__((visibility("default"))) const comply_plugin_api* comply_plugin_entry( \
      void) {                                                                                     \
    return ::comply::plugin::detail::Adapter<LawClass>::api(plugin_name);                         \
  }
