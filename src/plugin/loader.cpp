#include "comply/plugin/loader.hpp"

#include <dlfcn.h>

#include <array>
#include <cmath>
#include <cstdlib>
#include <sstream>
#include <system_error>

#include "comply/core/install_paths.hpp"
#include "comply/core/text_file.hpp"

namespace comply::plugin {
namespace {

std::string_view kindName(int kind) {
  switch (kind) {
    case COMPLY_COMMAND_JOINT:
      return "joint";
    case COMPLY_COMMAND_CARTESIAN:
      return "Cartesian";
    default:
      return "unknown";
  }
}

bool looksLikePath(std::string_view name_or_path) {
  return name_or_path.find('/') != std::string_view::npos || name_or_path.ends_with(".so");
}

}  // namespace

PluginError::PluginError(PluginErrc code, const std::string& message)
    : std::runtime_error(message), code_(code) {}

std::vector<std::filesystem::path> pluginSearchPath() {
  return searchPath("COMPLY_PLUGIN_PATH", COMPLY_PLUGIN_RELDIR, COMPLY_DEFAULT_PLUGIN_DIR);
}

std::filesystem::path resolvePlugin(std::string_view name_or_path) {
  if (looksLikePath(name_or_path)) {
    const std::filesystem::path path(name_or_path);
    std::error_code error;
    const auto status = std::filesystem::status(path, error);
    if (error && error != std::errc::no_such_file_or_directory) {
      // A symlink loop, a folder that cannot be searched: named, not reported as missing.
      throw PluginError(PluginErrc::kFileNotFound,
                        "plugin file '" + path.string() + "': " + fileErrorText(error));
    }
    if (!std::filesystem::is_regular_file(status)) {
      throw PluginError(PluginErrc::kFileNotFound,
                        "plugin file '" + path.string() + "' does not exist");
    }
    return path;
  }
  std::string tried;
  for (const auto& folder : pluginSearchPath()) {
    const auto candidate = folder / ("libcomply_" + std::string(name_or_path) + ".so");
    std::error_code error;  // a candidate that cannot be looked up is one more path tried
    if (std::filesystem::is_regular_file(candidate, error)) {
      return candidate;
    }
    tried += (tried.empty() ? "" : ", ") + candidate.string();
  }
  throw PluginError(PluginErrc::kFileNotFound,
                    "no plugin named '" + std::string(name_or_path) + "' (tried " + tried + ")");
}

PluginLibrary::PluginLibrary(std::string_view name_or_path, int expected_kind)
    // Absolute: dlopen() would search the library path for a bare file name instead of opening it.
    : path_(std::filesystem::absolute(resolvePlugin(name_or_path))) {
  handle_ = ::dlopen(path_.c_str(), RTLD_NOW | RTLD_LOCAL);
  if (handle_ == nullptr) {
    const char* reason = ::dlerror();
    throw PluginError(PluginErrc::kLoadFailed, "cannot load plugin '" + path_.string() +
                                                   "': " + (reason ? reason : "unknown error"));
  }
  ::dlerror();
  void* symbol = ::dlsym(handle_, COMPLY_ENTRY_SYMBOL);
  if (symbol == nullptr) {
    ::dlclose(handle_);
    throw PluginError(PluginErrc::kMissingEntry,
                      "plugin '" + path_.string() + "' does not export " + COMPLY_ENTRY_SYMBOL +
                          " (use COMPLY_EXPORT_CONTROLLER or define it in C)");
  }
  const auto entry = reinterpret_cast<comply_plugin_entry_fn>(symbol);
  api_ = entry();
  if (api_ == nullptr) {
    ::dlclose(handle_);
    throw PluginError(PluginErrc::kMissingEntry,
                      "plugin '" + path_.string() + "': " + COMPLY_ENTRY_SYMBOL + " returned NULL");
  }
  if (api_->abi_version != COMPLY_ABI_VERSION) {
    const auto found = api_->abi_version;
    ::dlclose(handle_);
    throw PluginError(PluginErrc::kAbiMismatch,
                      "plugin '" + path_.string() + "' was built for ABI version " +
                          std::to_string(found) + ", this comply expects " +
                          std::to_string(COMPLY_ABI_VERSION) + "; rebuild the plugin");
  }
  if (api_->create == nullptr || api_->destroy == nullptr || api_->step == nullptr ||
      api_->activate == nullptr || api_->required_quantities == nullptr) {
    ::dlclose(handle_);
    throw PluginError(PluginErrc::kMissingEntry,
                      "plugin '" + path_.string() + "' has an incomplete function table");
  }
  if (expected_kind != 0 && api_->command_kind != expected_kind) {
    const int found = api_->command_kind;
    ::dlclose(handle_);
    throw PluginError(PluginErrc::kWrongCommandKind,
                      "plugin '" + path_.string() + "' takes " + std::string(kindName(found)) +
                          " commands, but this wrapper sends " +
                          std::string(kindName(expected_kind)) + " commands");
  }
}

PluginLibrary::~PluginLibrary() {
  if (handle_ != nullptr) {
    ::dlclose(handle_);
  }
}

PluginInstance::PluginInstance(std::shared_ptr<const PluginLibrary> library, int dof,
                               const ParameterMap& parameters)
    : library_(std::move(library)), dof_(dof) {
  // Keep the storage alive for the duration of create(); plugins copy what they keep.
  std::vector<comply_parameter> items;
  items.reserve(parameters.size());
  for (const auto& [name, value] : parameters) {
    items.push_back({name.c_str(), value.is_text ? nullptr : value.numbers.data(),
                     static_cast<int32_t>(value.is_text ? 0 : value.numbers.size()),
                     value.is_text ? value.text.c_str() : nullptr});
  }
  const comply_parameters table{items.data(), static_cast<int32_t>(items.size())};
  std::array<char, 512> error{};
  // An exception from the plugin is the plugin's own type, perhaps none the host knows: it is
  // turned into a refusal naming the file here, where the call is made.
  const auto threw = [&](const char* function) {
    return PluginError(PluginErrc::kCreateFailed, "plugin '" + library_->path().string() +
                                                      "': " + function + " threw an exception");
  };
  try {
    instance_ = library_->api().create(dof, &table, error.data(), error.size());
  } catch (...) {
    throw threw("create()");
  }
  if (instance_ == nullptr) {
    throw PluginError(PluginErrc::kCreateFailed,
                      "plugin '" + library_->path().string() + "' refused its configuration: " +
                          (error[0] != '\0' ? error.data() : "no reason given"));
  }
  try {
    required_ = library_->api().required_quantities(instance_);
  } catch (...) {
    destroyInstance();
    throw threw("required_quantities()");
  }
}

PluginInstance::~PluginInstance() {
  destroyInstance();
}

void PluginInstance::destroyInstance() noexcept {
  if (instance_ == nullptr) {
    return;
  }
  try {
    library_->api().destroy(instance_);
  } catch (...) {
    // Nothing is left to do with an instance whose destruction failed; the host carries on.
  }
  instance_ = nullptr;
}

void PluginInstance::trialStep(const comply_input& input, const void* command) {
  comply_output output{};
  const comply_status status = step(input, command, output);
  if (status != COMPLY_OK) {
    output.message[COMPLY_MESSAGE_CAPACITY - 1] = '\0';
    throw PluginError(PluginErrc::kTrialStepFailed,
                      "plugin '" + library_->path().string() +
                          "' failed its activation trial step: " +
                          (output.message[0] != '\0' ? output.message : "no reason given"));
  }
  for (int i = 0; i < dof_; ++i) {
    if (!std::isfinite(output.torque[i])) {
      throw PluginError(PluginErrc::kNonFiniteOutput,
                        "plugin '" + library_->path().string() +
                            "' returned a non-finite torque for joint " + std::to_string(i) +
                            " in its activation trial step");
    }
  }
}

}  // namespace comply::plugin
