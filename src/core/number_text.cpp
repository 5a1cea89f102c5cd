#include "comply/core/number_text.hpp"

#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstdlib>

namespace comply {
namespace {

// Integers up to here read best in full (a gain of 1000000 N/m, 1000001 path samples); beyond,
// %g's exponent does (1e+300 m).
constexpr double kLargestFullInteger = 1e15;
constexpr int kDefaultDigits = 6;     // printf's %g
constexpr int kRoundTripDigits = 17;  // enough for any double to read back as itself

bool fullInteger(double x) {
  return std::abs(x) < kLargestFullInteger && x == std::trunc(x);
}

std::string withDigits(double x, int digits) {
  char text[40];
  std::snprintf(text, sizeof text, "%.*g", digits, x);
  return text;
}

}  // namespace

NumberTexts numbersApart(double value, double limit) {
  if (fullInteger(value) && fullInteger(limit)) {
    char value_text[24];
    char limit_text[24];
    std::snprintf(value_text, sizeof value_text, "%.0f", value);
    std::snprintf(limit_text, sizeof limit_text, "%.0f", limit);
    return {value_text, limit_text};
  }
  for (int digits = kDefaultDigits;; ++digits) {
    NumberTexts texts{withDigits(value, digits), withDigits(limit, digits)};
    // Compared as the numbers a reader sees, not as strings.
    if (digits == kRoundTripDigits ||
        std::strtod(texts.value.c_str(), nullptr) != std::strtod(texts.limit.c_str(), nullptr)) {
      return texts;
    }
  }
}

std::optional<double> finiteNumber(const std::string& text) {
  char* end = nullptr;
  errno = 0;
  const double value = std::strtod(text.c_str(), &end);
  // ERANGE: beyond double's range, or so small it lost precision (1e-400 reads as 0).
  if (end == text.c_str() || end != text.c_str() + text.size() || errno == ERANGE ||
      !std::isfinite(value)) {
    return std::nullopt;
  }
  return value;
}

}  // namespace comply
