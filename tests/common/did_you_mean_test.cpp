#include "rigid/common/did_you_mean.hpp"

#include <string>
#include <vector>

#include <gtest/gtest.h>

namespace rigid {
namespace {

const std::vector<std::string> kNames = {"solid_cylinder", "solid_sphere", "thin_rod", "t_end"};

TEST(DidYouMean, OneEditAway) {
  EXPECT_EQ(did_you_mean("solid_cilinder", kNames), "solid_cylinder");  // substitution
  EXPECT_EQ(did_you_mean("thin_ro", kNames), "thin_rod");               // deletion
  EXPECT_EQ(did_you_mean("t_ned", kNames), "t_end");                   // transposition
}

TEST(DidYouMean, NothingCloseGivesNothing) {
  EXPECT_FALSE(did_you_mean("rocket", kNames).has_value());
  EXPECT_EQ(did_you_mean_hint("rocket", kNames), "");
  EXPECT_EQ(did_you_mean_hint("thin_rd", kNames), "; did you mean 'thin_rod'?");
}

TEST(DidYouMean, ShortWordsAllowOneEdit) {
  const std::vector<std::string> short_names = {"rk4", "dt"};
  EXPECT_EQ(did_you_mean("rk5", short_names), "rk4");
  EXPECT_FALSE(did_you_mean("xy", short_names).has_value());  // two edits from "dt"
}

}  // namespace
}  // namespace rigid
