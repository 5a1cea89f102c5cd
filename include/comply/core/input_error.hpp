#pragma once
// The one error type for input a user wrote: controller files, task files, command JSON and
// command-line values. It carries a machine-readable code and where the problem is (file, key
// path, field), so a host can print "file: key.path: message" and a test can assert the code.

#include <stdexcept>
#include <string>
#include <string_view>

namespace comply {

enum class InputErrc {
  kCannotRead,    ///< the file does not exist or cannot be read
  kSyntax,        ///< not valid YAML / JSON
  kMissingKey,    ///< a required key is absent
  kUnknownKey,    ///< a key that no option or field has (typo)
  kWrongType,     ///< a string where a number belongs, a map where a list belongs, ...
  kWrongSize,     ///< a list with the wrong number of entries
  kOutOfRange,    ///< a number outside its allowed range (negative gain, NaN, ...)
  kInvalidValue,  ///< a value of the right type that is not allowed (unknown enum name, ...)
  kInconsistent,  ///< values that contradict each other or the robot
};

/// Name of a code as it appears in messages ("unknown_key", ...).
std::string_view toString(InputErrc code);

class InputError : public std::runtime_error {
 public:
  /// `source`: file name or "command" etc.; `key`: dotted key path ("initial.stiffness"), may be
  /// empty; `message`: what is wrong, without the source and key.
  InputError(InputErrc code, std::string source, std::string key, const std::string& message);

  [[nodiscard]] InputErrc code() const noexcept { return code_; }
  [[nodiscard]] const std::string& source() const noexcept { return source_; }
  [[nodiscard]] const std::string& key() const noexcept { return key_; }
  [[nodiscard]] const std::string& detail() const noexcept { return detail_; }

 private:
  InputErrc code_;
  std::string source_;
  std::string key_;
  std::string detail_;
};

}  // namespace comply
