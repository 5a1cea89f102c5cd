// Mesa's driver keeps state for the whole process in its own globals (about 240 bytes per
// renderer in the software driver). eglTerminate unloads the driver with the last display, which
// strands that memory: LeakSanitizer then reports it from code that is no longer mapped, which no
// suppression can name. Keeping the driver mapped keeps the memory reachable through its globals,
// and the next renderer in the process does not load the driver again.

#include "gl_driver.hpp"

#include <dlfcn.h>
#include <link.h>

#include <cstddef>
#include <string_view>

namespace comply::sim {
namespace {

bool isMesaDriver(std::string_view path) {
  const std::string_view file = path.substr(path.find_last_of('/') + 1);
  return file.ends_with("_dri.so") || file.starts_with("libgallium");
}

int pinIfMesaDriver(dl_phdr_info* info, std::size_t /*size*/, void* /*data*/) {
  if (info->dlpi_name != nullptr && isMesaDriver(info->dlpi_name)) {
    // RTLD_NOLOAD: only a library already loaded; RTLD_NODELETE: never unmapped. The extra
    // reference is intentionally never closed.
    dlopen(info->dlpi_name, RTLD_NOW | RTLD_NOLOAD | RTLD_NODELETE);
  }
  return 0;  // visit every loaded object
}

}  // namespace

void keepGlDriverLoaded() noexcept {
  dl_iterate_phdr(pinIfMesaDriver, nullptr);
}

}  // namespace comply::sim
