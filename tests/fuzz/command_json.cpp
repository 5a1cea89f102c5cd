// Fuzz target: a command as JSON text, read for both command kinds (what `comply send` and the
// validate samples take).
#include <cstddef>
#include <cstdint>
#include <exception>
#include <nlohmann/json.hpp>
#include <string>

#include "comply/schema/json.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  try {
    const nlohmann::json object = comply::schema::parseJson(text, "fuzz");
    (void)comply::schema::fromJson<comply::CartesianCommand>(object, 7);
    (void)comply::schema::fromJson<comply::JointCommand>(object, 6);
  } catch (const std::exception&) {
    // Refusing the input with a message is the expected outcome; crashing is not.
  }
  return 0;
}
