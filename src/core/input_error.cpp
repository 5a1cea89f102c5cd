#include "comply/core/input_error.hpp"

#include <utility>

#include "comply/core/enum_names.hpp"

namespace comply {
namespace {

std::string compose(const std::string& source, const std::string& key, const std::string& message) {
  std::string text = source;
  if (!key.empty()) {
    text += (text.empty() ? "" : ": ") + key;
  }
  return text + (text.empty() ? "" : ": ") + message;
}

constexpr EnumNames<InputErrc, 9> kInputErrcNames{{{InputErrc::kCannotRead, "cannot_read"},
                                                   {InputErrc::kSyntax, "syntax"},
                                                   {InputErrc::kMissingKey, "missing_key"},
                                                   {InputErrc::kUnknownKey, "unknown_key"},
                                                   {InputErrc::kWrongType, "wrong_type"},
                                                   {InputErrc::kWrongSize, "wrong_size"},
                                                   {InputErrc::kOutOfRange, "out_of_range"},
                                                   {InputErrc::kInvalidValue, "invalid_value"},
                                                   {InputErrc::kInconsistent, "inconsistent"}}};

}  // namespace

std::string_view toString(InputErrc code) {
  return nameIn(kInputErrcNames, code);
}

InputError::InputError(InputErrc code, std::string source, std::string key,
                       const std::string& message)
    : std::runtime_error(compose(source, key, message)),
      code_(code),
      source_(std::move(source)),
      key_(std::move(key)),
      detail_(message) {}

}  // namespace comply
