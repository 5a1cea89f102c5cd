#pragma once
// ASCII upper case: constant names (REASON_NON_FINITE) from their lower-case names.

#include <cctype>
#include <string>
#include <string_view>

namespace comply {

inline std::string upperCase(std::string_view text) {
  std::string out(text);
  for (char& c : out) {
    c = static_cast<char>(std::toupper(static_cast<unsigned char>(c)));
  }
  return out;
}

}  // namespace comply
