#pragma once
// Numbers in messages that compare a value with its limit. printf's %g keeps six significant
// digits, so an entry of 1000001 N/m once read "an entry of 1e+06 N/m, above the limit of 1e+06":
// the two are printed with as many digits as tell them apart.

#include <optional>
#include <string>

namespace comply {

/// A value and the limit it is compared with, as text.
struct NumberTexts {
  std::string value;
  std::string limit;
};

/// `value` and `limit` printed apart. Both integers below 1e15: in full ("1000001" beside
/// "1000000"). Otherwise both as %g with 6 significant digits, or as many more as make the printed
/// numbers differ ("0.12" beside "0.1", "0.5000000000000001" beside "0.5"; 17 digits tell any two
/// doubles apart). Both are rounded alike, so a value above its limit is printed above it.
NumberTexts numbersApart(double value, double limit);

/// The finite number that is the whole of `text` (strtod's syntax: "1e3", " 2", "-0.5"); nullopt
/// for "", "12abc", "nan", "inf", a value out of double's range or one that underflows.
std::optional<double> finiteNumber(const std::string& text);

}  // namespace comply
