#include "rigid/common/wording.hpp"

#include <gtest/gtest.h>

namespace rigid {
namespace {

TEST(Wording, SettingReferencesAreTheCppFields) {
  EXPECT_EQ(setting("shell"), "`shell = true`");
  EXPECT_EQ(setting("units", "mm"), "`units = \"mm\"`");
}

TEST(Wording, EachSurfaceWordsTheRemedy) {
  const std::string msg = "the mesh is open: use " + setting("shell") + ", or " +
                          setting("fill_holes") + "; if it is in millimetres, use " +
                          setting("units", "mm");
  EXPECT_EQ(word_for(Surface::kCli, msg),
            "the mesh is open: use --shell, or --fill-holes; if it is in millimetres, use --units mm");
  EXPECT_EQ(word_for(Surface::kPython, msg),
            "the mesh is open: use shell=True, or fill_holes=True; if it is in millimetres, use "
            "units=\"mm\"");
  const std::string scene = word_for(Surface::kScene, msg);
  EXPECT_EQ(scene, "the mesh is open: use 'shell = true', or 'fill_holes = true'; if it is in millimetres, use "
                   "'units = \"mm\"'");
  // a scene's wording is final: another front end showing it keeps it
  EXPECT_EQ(word_for(Surface::kPython, scene), scene);
  EXPECT_EQ(word_for(Surface::kLibrary, msg), msg);
}

TEST(Wording, OtherBackticksAreLeftAlone) {
  const std::string msg = "invariant `x > 0` fails; `a = b` and `k = 3` are not settings; `1x = true`";
  EXPECT_EQ(word_for(Surface::kCli, msg), msg);
  EXPECT_EQ(word_for(Surface::kPython, msg), msg);
  EXPECT_EQ(word_for(Surface::kCli, "unterminated `units = \"mm"), "unterminated `units = \"mm");
}

// A front end's user never called the C++ function that RIGID_REQUIRE names: the front ends'
// wording leaves it out, at the start and after the context a front end put before it.
TEST(Wording, FrontEndsDropCppFunctionNames) {
  EXPECT_EQ(word_for(Surface::kCli, "uniform(): 1 s of output"), "1 s of output");
  EXPECT_EQ(word_for(Surface::kScene, "s.toml:3:1: body 'b': make_primitive(): radius must be positive"),
            "s.toml:3:1: body 'b': radius must be positive");
  EXPECT_EQ(word_for(Surface::kPython, "rigid::io::write_run(): cannot write"), "cannot write");
  // the library keeps them (a C++ caller knows the entry point); calls in a text stay
  EXPECT_EQ(word_for(Surface::kLibrary, "uniform(): x"), "uniform(): x");
  EXPECT_EQ(word_for(Surface::kCli, "the value of sqrt(): 2"), "the value of sqrt(): 2");
  EXPECT_EQ(strip_function_names("a: b(): c: d(): e"), "a: c: e");
}

}  // namespace
}  // namespace rigid
