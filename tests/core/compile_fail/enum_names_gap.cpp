// Must not compile: the table skips a value (kB), which EnumNames refuses while compiling.
#include "comply/core/enum_names.hpp"

enum class Letter { kA, kB, kC };
constexpr comply::EnumNames<Letter, 2> kLetterNames{{{Letter::kA, "a"}, {Letter::kC, "c"}}};

int main() {
  return static_cast<int>(comply::nameIn(kLetterNames, Letter::kA).size());
}
