// Must not compile: the table lists the values out of order, which EnumNames refuses while
// compiling.
#include "comply/core/enum_names.hpp"

enum class Letter { kA, kB };
constexpr comply::EnumNames<Letter, 2> kLetterNames{{{Letter::kB, "b"}, {Letter::kA, "a"}}};

int main() {
  return static_cast<int>(comply::nameIn(kLetterNames, Letter::kA).size());
}
