#include "rigid/common/error.hpp"

#include <gtest/gtest.h>

#include "support/expect_error.hpp"

namespace rigid {
namespace {

double checked_radius(double r) {
  RIGID_REQUIRE(r > 0, "radius must be positive and finite, got {} m", r);
  return r;
}

TEST(Error, RequireNamesFunctionAndValue) {
  EXPECT_EQ(checked_radius(2.0), 2.0);
  EXPECT_RIGID_ERROR(checked_radius(-0.5),
                     "checked_radius(): radius must be positive and finite, got -0.5 m");
}

TEST(Error, SourceLocationFormats) {
  EXPECT_EQ(to_string(SourceLocation{"a.toml", 3, 7}), "a.toml:3:7");
  EXPECT_EQ(to_string(SourceLocation{"a.toml", 3, 0}), "a.toml:3");
  EXPECT_EQ(to_string(SourceLocation{"a.toml", 0, 0}), "a.toml");
  EXPECT_RIGID_ERROR(detail::throw_error_at(SourceLocation{"s.toml", 2, 5}, "bad key"),
                     "s.toml:2:5: bad key");
}

// A file name of any bytes is shown escaped, as rigid::escaped writes it: \xff for a byte
// that is not UTF-8, \x1b for ESC, so neither reaches a terminal raw.
TEST(Error, SourceLocationEscapesTheFileName) {
  EXPECT_EQ(to_string(SourceLocation{"a\xff\x1b.toml", 3, 4}), "a\\xff\\x1b.toml:3:4");
  EXPECT_EQ(to_string(SourceLocation{"b\xff.urdf", 7, 0}), "b\\xff.urdf:7");
  EXPECT_EQ(to_string(SourceLocation{"caf\xc3\xa9.toml", 0, 0}), "caf\xc3\xa9.toml");  // UTF-8 as is
}

TEST(Error, AssertThrowsInsteadOfAborting) {
  EXPECT_RIGID_ERROR(detail::throw_assertion("x > 0", "f.cpp", 12, "g"),
                     "internal error in g() at f.cpp:12: invariant `x > 0` does not hold");
}

}  // namespace
}  // namespace rigid
