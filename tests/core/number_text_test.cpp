// A value and its limit in one message are printed apart: "an entry of 1e+06 N/m, above the limit
// of 1e+06" told the reader nothing.

#include "comply/core/number_text.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <limits>

namespace comply {
namespace {

void expectTexts(double value, double limit, const std::string& value_text,
                 const std::string& limit_text) {
  const NumberTexts texts = numbersApart(value, limit);
  EXPECT_EQ(texts.value, value_text);
  EXPECT_EQ(texts.limit, limit_text);
}

TEST(NumbersApart, ShortNumbersStayShort) {
  expectTexts(100.5, 100.0, "100.5", "100");
  expectTexts(0.12, 0.1, "0.12", "0.1");
  expectTexts(0.7, 0.6, "0.7", "0.6");
  expectTexts(1e300, 0.1, "1e+300", "0.1");
  expectTexts(2.5e-7, 1e-7, "2.5e-07", "1e-07");
}

TEST(NumbersApart, IntegersArePrintedInFull) {
  expectTexts(1000001.0, 1e6, "1000001", "1000000");
  expectTexts(1e9, 1e6, "1000000000", "1000000");
  expectTexts(1e15, 1e6, "1e+15", "1e+06");  // beyond 1e15: the exponent reads better
}

TEST(NumbersApart, NumbersThatDifferArePrintedDifferentAndInOrder) {
  expectTexts(std::nextafter(0.5, 1.0), 0.5, "0.5000000000000001", "0.5");
  expectTexts(1000000.5, 1e6, "1000000.5", "1000000");
  expectTexts(0.100000001, 0.1, "0.100000001", "0.1");
  // 17 digits read back as the double itself: every two distinct doubles are told apart, and the
  // larger one is printed larger.
  for (const double limit : {0.1, 1.0 / 3.0, 100.0, 1e6 + 0.25, 123456.789}) {
    double value = limit;
    for (int step = 0; step < 5; ++step) {
      value = std::nextafter(value, std::numeric_limits<double>::infinity());
      const NumberTexts texts = numbersApart(value, limit);
      EXPECT_GT(std::strtod(texts.value.c_str(), nullptr),
                std::strtod(texts.limit.c_str(), nullptr))
          << texts.value << " vs " << texts.limit;
    }
  }
}

TEST(NumbersApart, NonFiniteValuesAreNamed) {
  expectTexts(std::numeric_limits<double>::infinity(), 100.0, "inf", "100");
  expectTexts(std::numeric_limits<double>::quiet_NaN(), 100.0, "nan", "100");
}

TEST(FiniteNumber, ReadsAWholeFiniteNumberAndNothingElse) {
  EXPECT_EQ(finiteNumber("10"), 10.0);
  EXPECT_EQ(finiteNumber("-2.5e-3"), -2.5e-3);
  EXPECT_EQ(finiteNumber(" 7"), 7.0);  // leading blanks, as strtod
  for (const std::string text :
       {"", " ", "12abc", "10 ", "nan", "inf", "-inf", "1e999", "1e-400", "hz"}) {
    EXPECT_FALSE(finiteNumber(text).has_value()) << "'" << text << "'";
  }
  EXPECT_FALSE(finiteNumber(std::string("1\0x", 3)).has_value()) << "the whole text, past a NUL";
}

}  // namespace
}  // namespace comply
