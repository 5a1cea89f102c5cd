// Compiles: the control for the two tables beside it that must not, so that their failure is the
// table's and not the test's set-up.
#include "comply/core/enum_names.hpp"

enum class Letter { kA, kB };
constexpr comply::EnumNames<Letter, 2> kLetterNames{{{Letter::kA, "a"}, {Letter::kB, "b"}}};

int main() {
  return static_cast<int>(comply::nameIn(kLetterNames, Letter::kA).size());
}
