// Fuzz target: a task file as YAML text, for a Cartesian and a 6-joint controller.
#include "comply/host/task_file.hpp"

#include <cstddef>
#include <cstdint>
#include <exception>
#include <string>

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  for (const bool cartesian : {true, false}) {
    try {
      (void)comply::host::parseTaskFile(text, "fuzz", "/nonexistent", cartesian, 6);
    } catch (const std::exception&) {
    }
  }
  return 0;
}
