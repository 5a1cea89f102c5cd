#pragma once
// A hardware backend: the arm `comply run --hardware NAME` drives. Built in (`sim`, the MuJoCo
// plant) or a shared library built out of tree against the installed package, like a control-law
// plugin (`comply plugin new NAME --kind hardware` writes the skeleton):
//
//   class MyArm final : public comply::hardware::HardwareInterface { ... };
//   COMPLY_HARDWARE_BACKEND(MyArm)   // MyArm(const comply::hardware::BackendContext&)
//
// The library exports three C symbols: comply_hardware_abi_version(), comply_hardware_create() and
// comply_hardware_destroy(). The interface between them is C++, so a backend is built with the
// comply release (and the compiler family) it runs under; the version check refuses any other
// with a clear message.

#include <cstdio>
#include <exception>
#include <filesystem>
#include <map>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "comply/hardware/hardware_interface.hpp"

namespace comply::hardware {

/// Bumped whenever BackendContext or HardwareInterface change layout or meaning.
inline constexpr int kBackendAbiVersion = 5;

/// What a backend learns about the controller it serves, once, before the first cycle.
struct BackendContext {
  std::string robot_name;
  std::filesystem::path robot_folder;  ///< holds robot.yaml and the URDF
  std::filesystem::path urdf_path;
  std::vector<std::string> joints;    ///< the controlled joints, in the controller's order
  std::vector<double> home_position;  ///< robot.yaml's home [rad | m], one per joint
  std::string tip_frame;              ///< the controller's TCP frame
  double period_s = 0.001;            ///< control period [s]
  /// `--hardware-option key=value` pairs (address, port, ...): the backend's own settings.
  std::map<std::string, std::string> options;
};

class BackendError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

}  // namespace comply::hardware

/// The entry points of a backend library (see the top of this file). `error` receives why the
/// backend refused to start (it then returns nullptr); at most `error_size` bytes, NUL included.
extern "C" {
using ComplyHardwareAbiVersionFn = int (*)();
using ComplyHardwareCreateFn =
    comply::hardware::HardwareInterface* (*)(const comply::hardware::BackendContext* context,
                                             char* error, unsigned long error_size);
using ComplyHardwareDestroyFn = void (*)(comply::hardware::HardwareInterface* hardware);
}

namespace comply::hardware {

/// A backend library's HardwareInterface, owning the library it came from. The interface is
/// destroyed by the library's own comply_hardware_destroy (it was allocated in the library, which
/// may use another allocator), and only then is the library unloaded: its code must outlive every
/// call into the interface. Move-only, like std::unique_ptr; empty once moved from.
class BackendHandle {
 public:
  BackendHandle() noexcept = default;
  /// Takes over `hardware` (from `library`'s create) and the dlopen() handle `library`.
  BackendHandle(HardwareInterface* hardware, ComplyHardwareDestroyFn destroy,
                void* library) noexcept
      : hardware_(hardware), destroy_(destroy), library_(library) {}
  ~BackendHandle() { reset(); }
  BackendHandle(BackendHandle&& other) noexcept
      : hardware_(std::exchange(other.hardware_, nullptr)),
        destroy_(std::exchange(other.destroy_, nullptr)),
        library_(std::exchange(other.library_, nullptr)) {}
  BackendHandle& operator=(BackendHandle&& other) noexcept {
    if (this != &other) {
      reset();
      hardware_ = std::exchange(other.hardware_, nullptr);
      destroy_ = std::exchange(other.destroy_, nullptr);
      library_ = std::exchange(other.library_, nullptr);
    }
    return *this;
  }
  BackendHandle(const BackendHandle&) = delete;
  BackendHandle& operator=(const BackendHandle&) = delete;

  [[nodiscard]] HardwareInterface* get() const noexcept { return hardware_; }
  HardwareInterface& operator*() const noexcept { return *hardware_; }
  HardwareInterface* operator->() const noexcept { return hardware_; }
  explicit operator bool() const noexcept { return hardware_ != nullptr; }

  /// Destroys the interface, then unloads the library; the handle is empty afterwards.
  void reset() noexcept;

 private:
  HardwareInterface* hardware_ = nullptr;
  ComplyHardwareDestroyFn destroy_ = nullptr;
  void* library_ = nullptr;  ///< from dlopen()
};

/// Loads `library` (a path to a .so), checks its version and creates its HardwareInterface for
/// `context`. Throws BackendError naming the library and what failed (not found, not a backend,
/// another version, the backend's own refusal).
BackendHandle loadBackendLibrary(const std::filesystem::path& library,
                                 const BackendContext& context);

}  // namespace comply::hardware

#define COMPLY_HARDWARE_BACKEND(Class)                                                   \
  extern "C" __attribute__((visibility("default"))) int comply_hardware_abi_version() {  \
    return comply::hardware::kBackendAbiVersion;                                         \
  }                                                                                      \
  extern "C" __attribute__((visibility("default"))) comply::hardware::HardwareInterface* \
  comply_hardware_create(const comply::hardware::BackendContext* context, char* error,   \
                         unsigned long error_size) {                                     \
    try {                                                                                \
      return new Class(*context);                                                        \
    } catch (const std::exception& failure) {                                            \
      if (error != nullptr && error_size > 0) {                                          \
        std::snprintf(error, error_size, "%s", failure.what());                          \
      }                                                                                  \
      return nullptr;                                                                    \
    }                                                                                    \
  }                                                                                      \
  extern "C" __attribute__((visibility("default"))) void comply_hardware_destroy(        \
      comply::hardware::HardwareInterface* hardware) {                                   \
    delete hardware;                                                                     \
  }
