#include "task_file_reading.hpp"

#include <cmath>
#include <sstream>

namespace comply::host::task_reading {

using nlohmann::json;

std::vector<double> numbers(const json& value, std::size_t count, const std::string& where,
                            const TaskError& error) {
  std::vector<double> out;
  if (!value.is_array()) {
    error.fail(where, "must be a list of " + std::to_string(count) + " numbers");
  }
  for (const json& entry : value) {
    if (!entry.is_number()) {
      error.fail(where, "must be a list of " + std::to_string(count) + " numbers");
    }
    out.push_back(entry.get<double>());
  }
  if (out.size() != count) {
    error.fail(where,
               "has " + std::to_string(out.size()) + " numbers, expected " + std::to_string(count));
  }
  return out;
}

void checkUnitQuaternion(const std::vector<double>& quaternion, double tolerance,
                         const std::string& where, const TaskError& error) {
  const double norm = std::sqrt(quaternion[0] * quaternion[0] + quaternion[1] * quaternion[1] +
                                quaternion[2] * quaternion[2] + quaternion[3] * quaternion[3]);
  if (std::abs(norm - 1.0) > tolerance) {
    std::ostringstream message;
    message << "is not a unit quaternion (x y z w): its norm is " << norm;
    error.fail(where, message.str());
  }
}

double positiveNumber(const json& object, const std::string& key, double fallback,
                      const std::string& where, const TaskError& error) {
  if (!object.contains(key)) {
    return fallback;
  }
  if (!object[key].is_number() || !(object[key].get<double>() > 0.0) ||
      !std::isfinite(object[key].get<double>())) {
    error.fail(where + "." + key, "must be a finite number > 0");
  }
  return object[key].get<double>();
}

}  // namespace comply::host::task_reading
