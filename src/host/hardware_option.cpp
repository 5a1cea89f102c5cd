// --hardware-option values (hardware_option.hpp).

#include "hardware_option.hpp"

#include <charconv>
#include <cmath>

#include "comply/hardware/backend.hpp"

namespace comply::host {

double numberOption(const std::string& key, const std::string& text) {
  double value = 0.0;
  const auto [end, error] = std::from_chars(text.data(), text.data() + text.size(), value);
  if (error != std::errc() || end != text.data() + text.size() || !std::isfinite(value)) {
    throw hardware::BackendError("--hardware-option " + key + "='" + text + "' is not a number");
  }
  return value;
}

std::uint16_t portOption(const std::string& key, const std::string& text) {
  const double port = numberOption(key, text);
  if (port < 1 || port > 65535 || port != std::floor(port)) {
    throw hardware::BackendError("--hardware-option " + key + "=" + text +
                                 " is not a TCP port (1 to 65535)");
  }
  return static_cast<std::uint16_t>(port);
}

}  // namespace comply::host
