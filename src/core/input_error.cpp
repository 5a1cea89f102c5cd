#include "comply/core/input_error.hpp"

#include <utility>

namespace comply {
namespace {

std::string compose(const std::string& source, const std::string& key, const std::string& message) {
  std::string text = source;
  if (!key.empty()) {
    text += (text.empty() ? "" : ": ") + key;
  }
  return text + (text.empty() ? "" : ": ") + message;
}

}  // namespace

std::string_view toString(InputErrc code) {
  switch (code) {
    case InputErrc::kCannotRead:
      return "cannot_read";
    case InputErrc::kSyntax:
      return "syntax";
    case InputErrc::kMissingKey:
      return "missing_key";
    case InputErrc::kUnknownKey:
      return "unknown_key";
    case InputErrc::kWrongType:
      return "wrong_type";
    case InputErrc::kWrongSize:
      return "wrong_size";
    case InputErrc::kOutOfRange:
      return "out_of_range";
    case InputErrc::kInvalidValue:
      return "invalid_value";
    case InputErrc::kInconsistent:
      return "inconsistent";
  }
  return "unknown";
}

InputError::InputError(InputErrc code, std::string source, std::string key,
                       const std::string& message)
    : std::runtime_error(compose(source, key, message)),
      code_(code),
      source_(std::move(source)),
      key_(std::move(key)),
      detail_(message) {}

}  // namespace comply
