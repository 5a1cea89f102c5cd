#pragma once
// One --hardware-option value read as what a backend takes (ur_backend.cpp, franka_backend.cpp):
// a hardware::BackendError naming the option when it is not.

#include <cstdint>
#include <string>

namespace comply::host {

/// A finite number.
double numberOption(const std::string& key, const std::string& text);
/// A TCP port, 1 to 65535.
std::uint16_t portOption(const std::string& key, const std::string& text);

}  // namespace comply::host
