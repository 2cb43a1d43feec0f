// A real in a deck's columns (solver/deck_writer/number_field.h): the shortest text that reads
// back to the same double, the shorter spellings when they make it fit, the most digits that
// fit otherwise (flagged inexact).
#include "solver/deck_writer/number_field.h"

#include <gtest/gtest.h>

#include <cstdlib>
#include <random>

#include "core/errors.h"

namespace crashlink::deck_writer {
namespace {

TEST(NumberField, ShortestExactText) {
  EXPECT_EQ(format_real(0.0, 10).text, "0.0");
  EXPECT_EQ(format_real(7850.0, 10).text, "7850.");
  EXPECT_EQ(format_real(0.3, 10).text, ".3");
  EXPECT_EQ(format_real(-0.5, 10).text, "-.5");
  EXPECT_EQ(format_real(2.1e11, 10).text, "2.1e11");
  EXPECT_EQ(format_real(1e-5, 10).text, "1e-5");
  EXPECT_EQ(format_real(-0.18000000000000002, 20).text, "-.18000000000000002");
  // 16 digits of generator noise: as an integer mantissa, which fits 20 columns
  EXPECT_EQ(format_real(6.938893903907228e-18, 20).text, "6938893903907228e-33");
  EXPECT_TRUE(format_real(6.938893903907228e-18, 20).exact);
}

TEST(NumberField, TooManyDigitsAreRoundedAndSaidSo) {
  const auto n = format_real(-6.938893903907228e-18, 20);  // 21 characters exact
  EXPECT_FALSE(n.exact);
  EXPECT_LE(n.text.size(), 20u);
  EXPECT_NEAR(std::strtod(n.text.c_str(), nullptr), -6.938893903907228e-18, 1e-14 * 6.9e-18);
  EXPECT_EQ(format_real(1.0 / 3.0, 10).text.size(), 10u);
  EXPECT_THROW(format_real(std::nan(""), 10), ModelError);
}

// Every double of a coordinate's range that fits 20 columns reads back to itself.
TEST(NumberField, RandomCoordinatesReadBack) {
  std::mt19937_64 gen(7);
  std::uniform_real_distribution<double> x(-2.0, 2.0);
  int inexact = 0;
  for (int k = 0; k < 100000; ++k) {
    const double v = x(gen);
    const auto n = format_real(v, 20);
    ASSERT_LE(n.text.size(), 20u);
    if (n.exact) {
      ASSERT_EQ(std::strtod(n.text.c_str(), nullptr), v) << n.text;
    } else {
      ++inexact;
    }
  }
  EXPECT_LT(inexact, 2000) << "only values below 0.01 with 17 digits can miss";
}

}  // namespace
}  // namespace crashlink::deck_writer
