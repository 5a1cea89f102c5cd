// Fuzz target: a controller file as YAML text, read as `comply sim --config` reads it.
#include <cstddef>
#include <cstdint>
#include <exception>
#include <string>

#include "comply/pipeline/config.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  try {
    (void)comply::pipeline::parseWrapperText(text, "fuzz");
  } catch (const std::exception&) {
  }
  return 0;
}
