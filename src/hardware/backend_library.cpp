// Loading a hardware backend library (include/comply/hardware/backend.hpp). Every refusal names
// the file and the cause: the user typed the path, and a driver fails in many ways.
#include <dlfcn.h>

#include <array>
#include <exception>
#include <string>
#include <system_error>
#include <utility>

#include "comply/core/text_file.hpp"
#include "comply/hardware/backend.hpp"

namespace comply::hardware {
namespace {

/// Closes a dlopen() handle on every early return of the loader; release() hands it over.
class LibraryGuard {
 public:
  explicit LibraryGuard(void* handle) noexcept : handle_(handle) {}
  ~LibraryGuard() {
    if (handle_ != nullptr) {
      ::dlclose(handle_);
    }
  }
  LibraryGuard(const LibraryGuard&) = delete;
  LibraryGuard& operator=(const LibraryGuard&) = delete;

  [[nodiscard]] void* get() const noexcept { return handle_; }
  void* release() noexcept { return std::exchange(handle_, nullptr); }

 private:
  void* handle_;
};

BackendError failure(const std::filesystem::path& library, const std::string& reason) {
  return BackendError("hardware backend '" + library.string() + "': " + reason);
}

/// The address of `symbol`, or a BackendError saying the library is not a backend.
void* entryPoint(void* handle, const std::filesystem::path& library, const char* symbol) {
  void* address = ::dlsym(handle, symbol);
  if (address == nullptr) {
    throw failure(library, std::string("not a comply hardware backend (no ") + symbol + ")");
  }
  return address;
}

}  // namespace

void BackendHandle::reset() noexcept {
  if (hardware_ != nullptr && destroy_ != nullptr) {
    try {
      destroy_(hardware_);
    } catch (...) {
      // A destructor that throws leaves nothing to recover; the host goes on shutting down.
    }
  }
  hardware_ = nullptr;
  destroy_ = nullptr;
  // Only now: destroy_ and the interface's destructor are code of this library.
  if (library_ != nullptr) {
    ::dlclose(library_);
    library_ = nullptr;
  }
}

BackendHandle loadBackendLibrary(const std::filesystem::path& library,
                                 const BackendContext& context) {
  // Absolute: dlopen() would search the library path for a bare file name instead of opening it.
  const std::filesystem::path path = std::filesystem::absolute(library);
  std::error_code error;
  const auto status = std::filesystem::status(path, error);
  if (error || !std::filesystem::exists(status)) {
    throw failure(path, fileErrorText(error));  // a symlink loop named as one, not as missing
  }
  if (!std::filesystem::is_regular_file(status)) {
    throw failure(path, "not a regular file");
  }
  // RTLD_LOCAL: two backends, or a backend and a plugin, may define the same names.
  LibraryGuard handle(::dlopen(path.c_str(), RTLD_NOW | RTLD_LOCAL));
  if (handle.get() == nullptr) {
    const char* reason = ::dlerror();
    throw failure(path, std::string("cannot load it: ") + (reason ? reason : "unknown error"));
  }
  // create first: a library that is no backend at all is named as such, not as a version problem.
  const auto create = reinterpret_cast<ComplyHardwareCreateFn>(
      entryPoint(handle.get(), path, "comply_hardware_create"));
  const auto abi_version = reinterpret_cast<ComplyHardwareAbiVersionFn>(
      entryPoint(handle.get(), path, "comply_hardware_abi_version"));
  const auto destroy = reinterpret_cast<ComplyHardwareDestroyFn>(
      entryPoint(handle.get(), path, "comply_hardware_destroy"));

  // Before create(): a backend built for another version would read the context wrongly.
  if (const int found = abi_version(); found != kBackendAbiVersion) {
    throw failure(path, "built for backend interface version " + std::to_string(found) +
                            ", this comply has " + std::to_string(kBackendAbiVersion) +
                            "; rebuild it against this comply");
  }

  std::array<char, 512> reason{};
  HardwareInterface* hardware = nullptr;
  // COMPLY_HARDWARE_BACKEND catches what the constructor throws; a library defining
  // comply_hardware_create by hand may not, and its exception still names no library.
  try {
    hardware = create(&context, reason.data(), reason.size());
  } catch (const std::exception& thrown) {
    throw failure(path, std::string("refused to start: ") + thrown.what());
  } catch (...) {
    throw failure(path, "refused to start: comply_hardware_create threw an exception");
  }
  if (hardware == nullptr) {
    reason.back() = '\0';  // the backend may have filled the buffer without terminating it
    throw failure(path, std::string("refused to start: ") +
                            (reason.front() != '\0' ? reason.data() : "no reason given"));
  }
  return BackendHandle(hardware, destroy, handle.release());
}

}  // namespace comply::hardware
