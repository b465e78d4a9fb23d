// The rigid command-line tool: CLI11 parsing and the single error exit path.
#include <cstdio>
#include <exception>

#include <CLI/CLI.hpp>

#include "rigid/common/error.hpp"
#include "rigid/common/wording.hpp"
#include "rigid/version.hpp"

// One header per subcommand, each defining add_<verb>_command(CLI::App&).
#include "cli_demo.hpp"
#include "cli_inertia.hpp"
#include "cli_rotation.hpp"
#include "cli_mesh.hpp"
#include "cli_run.hpp"

int main(int argc, char** argv) {
  CLI::App app{
      "rigid: rigid-body mechanics from isometries and inertia tensors to Euler's equations.\n"
      "SI units throughout; quaternions are (w, x, y, z) unless an option says otherwise."};
  app.set_version_flag("--version", std::string("rigid ") + RIGID_VERSION_STRING);
  app.require_subcommand(0, 1);

  add_demo_command(app);
  add_inertia_command(app);
  add_rotation_command(app);
  add_mesh_command(app);
  add_run_command(app);

  try {
    app.parse(argc, argv);
    if (app.get_subcommands().empty()) {
      std::fputs(app.help().c_str(), stderr);
      std::fputs("rigid: error: a subcommand is required (see the list above)\n", stderr);
      return 2;
    }
  } catch (const CLI::ParseError& e) {
    // CLI11's own messages for --help, --version and bad command lines.
    return app.exit(e);
  } catch (const rigid::Cancelled& e) {
    std::fprintf(stderr, "rigid: interrupted: %s\n", e.what());
    return 130;  // the shell's code for a command stopped by SIGINT
  } catch (const rigid::Error& e) {
    // the library names its settings in its own terms; here they are flags
    std::fprintf(stderr, "rigid: error: %s\n", rigid::word_for(rigid::Surface::kCli, e.what()).c_str());
    return 1;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "rigid: error: %s\n", e.what());
    return 1;
  }
  return 0;
}
