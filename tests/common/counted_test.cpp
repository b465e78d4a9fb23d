#include "rigid/common/wording.hpp"

#include <gtest/gtest.h>

namespace rigid {
namespace {

// "1 boundary edges" was printed: a count of one takes the singular.
TEST(Counted, SingularForOneAndPluralOtherwise) {
  EXPECT_EQ(counted(1, "boundary edge"), "1 boundary edge");
  EXPECT_EQ(counted(0, "boundary edge"), "0 boundary edges");
  EXPECT_EQ(counted(3, "boundary edge"), "3 boundary edges");
  EXPECT_EQ(counted(1, "body", "bodies"), "1 body");
  EXPECT_EQ(counted(2, "body", "bodies"), "2 bodies");
}

}  // namespace
}  // namespace rigid
