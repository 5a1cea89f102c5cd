#pragma once
// Loads a control-law plugin (a shared library exporting comply_plugin_entry) and owns one
// instance of it. Every refusal names the file and the cause.

#include <cstring>
#include <filesystem>
#include <map>
#include <memory>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

#include "comply/plugin/abi.h"

namespace comply::plugin {

enum class PluginErrc {
  kFileNotFound,      ///< no such file, or no plugin of that name on the plugin path
  kLoadFailed,        ///< dlopen failed (not a shared library, missing dependency, ...)
  kMissingEntry,      ///< the library does not export comply_plugin_entry
  kAbiMismatch,       ///< built against another COMPLY_ABI_VERSION
  kWrongCommandKind,  ///< a joint law in a Cartesian wrapper or vice versa
  kCreateFailed,      ///< the plugin refused its parameters
  kTrialStepFailed,   ///< the activation trial step returned an error
  kNonFiniteOutput,   ///< the activation trial step returned a NaN or infinite torque
};

class PluginError : public std::runtime_error {
 public:
  PluginError(PluginErrc code, const std::string& message);
  [[nodiscard]] PluginErrc code() const noexcept { return code_; }

 private:
  PluginErrc code_;
};

/// A parameter value as read from configuration: numbers or a string.
struct ParameterValue {
  std::vector<double> numbers;
  std::string text;
  bool is_text = false;
};
using ParameterMap = std::map<std::string, ParameterValue>;

/// Folders searched for plugin names: $COMPLY_PLUGIN_PATH (':'-separated), then the build's
/// controllers folder. A name `foo` resolves to `libcomply_foo.so`.
std::vector<std::filesystem::path> pluginSearchPath();

/// Resolves a plugin name or path to a file; throws kFileNotFound listing what was tried.
std::filesystem::path resolvePlugin(std::string_view name_or_path);

class PluginLibrary {
 public:
  /// dlopen + entry-point and ABI checks. `expected_kind` 0 accepts either kind.
  explicit PluginLibrary(std::string_view name_or_path, int expected_kind = 0);
  ~PluginLibrary();
  PluginLibrary(const PluginLibrary&) = delete;
  PluginLibrary& operator=(const PluginLibrary&) = delete;

  [[nodiscard]] const comply_plugin_api& api() const noexcept { return *api_; }
  [[nodiscard]] const std::filesystem::path& path() const noexcept { return path_; }

 private:
  std::filesystem::path path_;
  void* handle_ = nullptr;
  const comply_plugin_api* api_ = nullptr;
};

/// One configured instance of a plugin; keeps its library loaded.
class PluginInstance {
 public:
  PluginInstance(std::shared_ptr<const PluginLibrary> library, int dof,
                 const ParameterMap& parameters);
  ~PluginInstance();
  PluginInstance(const PluginInstance&) = delete;
  PluginInstance& operator=(const PluginInstance&) = delete;

  [[nodiscard]] std::uint32_t requiredQuantities() const noexcept { return required_; }
  [[nodiscard]] const PluginLibrary& library() const noexcept { return *library_; }
  [[nodiscard]] int dof() const noexcept { return dof_; }

  /// The law's activation. An exception thrown through the C ABI (a C++ law written without the
  /// SDK) is a failed activation, never the end of the process.
  comply_status activate(const comply_input& input) noexcept {
    try {
      return library_->api().activate(instance_, &input);
    } catch (...) {
      return COMPLY_ERROR;
    }
  }
  /// The law's step. An exception thrown through the C ABI becomes a failed step with a message;
  /// catching by `...` neither allocates nor costs anything when nothing is thrown.
  comply_status step(const comply_input& input, const void* command,
                     comply_output& output) noexcept {
    try {
      return library_->api().step(instance_, &input, command, &output);
    } catch (...) {
      static constexpr char kThrew[] = "step threw an exception";
      static_assert(sizeof kThrew <= COMPLY_MESSAGE_CAPACITY);
      std::memcpy(output.message, kThrew, sizeof kThrew);
      return COMPLY_ERROR;
    }
  }

  /// Runs one step outside the real-time loop and throws kTrialStepFailed / kNonFiniteOutput if
  /// the law errors or returns a non-finite torque. Used on activation, before any torque is sent.
  void trialStep(const comply_input& input, const void* command);

 private:
  /// The plugin's destroy(), once; an exception from it is swallowed (destructors must not throw).
  void destroyInstance() noexcept;

  std::shared_ptr<const PluginLibrary> library_;
  void* instance_ = nullptr;
  std::uint32_t required_ = 0;
  int dof_ = 0;
};

}  // namespace comply::plugin
