// Uses the installed headers and libraries; exits non-zero if anything is off.
#include <cstdio>

#include <rigid/common/error.hpp>
#include <rigid/version.hpp>

int main() {
  try {
    RIGID_REQUIRE(1 + 1 == 3, "expected {}", 3);
  } catch (const rigid::Error& e) {
    std::printf("rigid %s: caught \"%s\"\n", RIGID_VERSION_STRING, e.what());
    return 0;
  }
  return 1;
}
