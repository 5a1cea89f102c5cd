#pragma once
// What the task-file reader's parts share: the error that names the file and the key, and the
// checked readers of numbers, vectors and quaternions.

#include <cstddef>
#include <nlohmann/json.hpp>
#include <stdexcept>
#include <string>
#include <vector>

namespace comply::host::task_reading {

class TaskError {
 public:
  explicit TaskError(std::string source) : source_(std::move(source)) {}
  [[nodiscard]] const std::string& source() const { return source_; }
  [[noreturn]] void fail(const std::string& where, const std::string& message) const {
    throw std::runtime_error(source_ + ": " + (where.empty() ? "" : where + ": ") + message);
  }

 private:
  std::string source_;
};

/// A JSON list of exactly `count` numbers, else TaskError.
std::vector<double> numbers(const nlohmann::json& value, std::size_t count,
                            const std::string& where, const TaskError& error);
/// Unit norm within `tolerance`, else TaskError.
void checkUnitQuaternion(const std::vector<double>& quaternion, double tolerance,
                         const std::string& where, const TaskError& error);
/// object[key] as a finite number > 0, `fallback` when absent.
double positiveNumber(const nlohmann::json& object, const std::string& key, double fallback,
                      const std::string& where, const TaskError& error);

}  // namespace comply::host::task_reading
