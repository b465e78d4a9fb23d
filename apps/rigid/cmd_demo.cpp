#include "cmd_demo.hpp"

#include <fmt/core.h>

#include "rigid/version.hpp"

namespace rigid::cli {

void run_demo() {
  fmt::print("rigid {}: the modules of this build are listed by `rigid --help`.\n",
             RIGID_VERSION_STRING);
}

}  // namespace rigid::cli
