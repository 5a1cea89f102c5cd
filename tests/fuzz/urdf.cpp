// Fuzz target: a URDF, built into a model for the chain base -> tip over joints j1, j2 (the seed
// corpus holds such robots) and for the chain its first and last links span.
#include <cstddef>
#include <cstdint>
#include <exception>
#include <string>

#include "comply/model/model.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  comply::model::ModelOptions options;
  options.base_frame = "base";
  options.tip_frame = "tip";
  options.joint_names = {"j1", "j2"};
  try {
    (void)comply::model::Model::fromUrdfString(text, options);
  } catch (const std::exception&) {
  }
  return 0;
}
