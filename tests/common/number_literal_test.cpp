#include "rigid/common/number_literal.hpp"

#include <limits>

#include <gtest/gtest.h>

namespace rigid {
namespace {

// The bounds are the IEEE 754 binary64 limits, as <limits> has them.
TEST(NumberLiteral, BoundsAreTheNormalRangeOfADouble) {
  EXPECT_EQ(kSmallestLiteral, std::numeric_limits<double>::min());
  EXPECT_EQ(kLargestLiteral, std::numeric_limits<double>::max());
}

TEST(NumberLiteral, AcceptsZeroAndTheNormalRange) {
  for (const char* s :
       {"0", "0.0", "-0.0", "0e-999", "0.000e+400", "1", "9.81", "-2.5e3", "1_000.5",
        "2.2250738585072014e-308", "1.7976931348623157e308", "-1.7976931348623157e+308"}) {
    EXPECT_FALSE(literal_range_problem(s).has_value()) << s;
  }
}

TEST(NumberLiteral, RefusesAnUnderflowToZeroSayingWhatWasWritten) {
  const auto p = literal_range_problem("1e-400");
  ASSERT_TRUE(p.has_value());
  EXPECT_NE(p->find("'1e-400' underflows"), std::string::npos) << *p;
  EXPECT_NE(p->find("would hold 0"), std::string::npos) << *p;
  EXPECT_NE(p->find("2.2250738585072014e-308 to 1.7976931348623157e+308"), std::string::npos) << *p;
}

TEST(NumberLiteral, RefusesASubnormal) {
  // 2^-1022 / 10 and the smallest subnormal 2^-1074 ≈ 4.94e-324: both below DBL_MIN
  for (const char* s : {"2.2250738585072014e-309", "4.9e-324", "-1e-310"}) {
    const auto p = literal_range_problem(s);
    ASSERT_TRUE(p.has_value()) << s;
    EXPECT_NE(p->find("subnormal"), std::string::npos) << *p;
  }
}

TEST(NumberLiteral, RefusesAnOverflow) {
  const auto p = literal_range_problem("-1.8e308");
  ASSERT_TRUE(p.has_value());
  EXPECT_NE(p->find("'-1.8e308' overflows: a double would hold -infinity"), std::string::npos)
      << *p;
}

TEST(NumberLiteral, LeavesNonLiteralsToTheCaller) {
  for (const char* s : {"", "inf", "nan", "L", "1e-400*L", "0x10", "1e"}) {
    EXPECT_FALSE(literal_range_problem(s).has_value()) << s;
  }
  EXPECT_EQ(leading_literal("1e-400, 0]"), "1e-400");
  EXPECT_EQ(leading_literal("-2.5E+3_0 #"), "-2.5E+3_0");
  EXPECT_EQ(leading_literal("x"), "");
}

}  // namespace
}  // namespace rigid
