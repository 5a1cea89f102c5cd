// Must not compile: two enumerators share a name, which EnumNames refuses while compiling.
#include "comply/core/enum_names.hpp"

enum class Letter { kA, kB };
constexpr comply::EnumNames<Letter, 2> kLetterNames{{{Letter::kA, "a"}, {Letter::kB, "a"}}};

int main() {
  return static_cast<int>(comply::nameIn(kLetterNames, Letter::kA).size());
}
