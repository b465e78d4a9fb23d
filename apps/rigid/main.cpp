// The rigid command-line tool: CLI11 parsing and the single error exit path.
#include <cstdio>
#include <exception>
#include <new>

#include <CLI/CLI.hpp>

#include "cli_error.hpp"
#include "rigid/common/error.hpp"
#include "rigid/common/wording.hpp"
#include "rigid/version.hpp"

// One header per subcommand, each defining add_<verb>_command(CLI::App&).
#include "cli_demo.hpp"
#include "cli_inertia.hpp"
#include "cli_rotation.hpp"
#include "cli_mesh.hpp"
#include "cli_modes.hpp"
#include "cli_plot.hpp"
#include "cli_run.hpp"
#include "cli_suggest.hpp"
#include "cli_sweep.hpp"

namespace {
// The exit status of every subcommand (documented in the --help footer, README and
// docs/reliability.md).
constexpr int kExitOk = 0;
constexpr int kExitRefused = 1;      // a rigid::Error: the input was refused with a reason
constexpr int kExitUsage = 2;        // the command line itself is wrong
constexpr int kExitInterrupted = 130;  // Ctrl-C (the shell's 128 + SIGINT)
}  // namespace

int main(int argc, char** argv) {
  CLI::App app{
      "rigid: rigid-body mechanics from isometries and inertia tensors to Euler's equations.\n"
      "SI units throughout; quaternions are (w, x, y, z) unless an option says otherwise."};
  app.set_version_flag("--version", std::string("rigid ") + RIGID_VERSION_STRING);
  app.require_subcommand(0, 1);
  app.footer(
      "Exit status (every subcommand): 0 success; 1 refused input (a file, a scene, a value: the "
      "message says what, where and what was expected); 2 usage (an unknown subcommand or option, a "
      "missing or conflicting option, an option value that is none of its forms: an unknown name, a "
      "malformed number or list, a number no double holds); 130 interrupted (Ctrl-C; nothing is "
      "written).");

  add_demo_command(app);
  add_inertia_command(app);
  add_rotation_command(app);
  add_mesh_command(app);
  add_run_command(app);
  add_modes_command(app);
  add_sweep_command(app);
  add_plot_command(app);

  // One rule for empty arguments, before CLI11 sees them (an empty positional followed by an
  // option sent its parser into an endless loop): no argument of rigid may be empty.
  for (int i = 1; i < argc; ++i) {
    if (argv[i][0] == '\0') {
      std::fprintf(stderr,
                   "rigid: error: argument %d is empty%s%s%s; every argument needs a value (a file, a "
                   "number, a name): remove it or give one\n",
                   i, i > 1 ? " (after '" : "", i > 1 ? argv[i - 1] : "", i > 1 ? "')" : "");
      return kExitUsage;
    }
  }
  try {
    rigid::cli::refuse_misspelt_names(app, argc, argv);
    app.parse(argc, argv);
    if (app.get_subcommands().empty()) {
      std::fputs(app.help().c_str(), stderr);
      std::fputs("rigid: error: a subcommand is required (see the list above)\n", stderr);
      return kExitUsage;
    }
  } catch (const CLI::CallForHelp& e) {
    return app.exit(e);  // --help: the text on stdout, 0
  } catch (const CLI::CallForAllHelp& e) {
    return app.exit(e);
  } catch (const CLI::CallForVersion& e) {
    return app.exit(e);
  } catch (const CLI::ParseError& e) {
    // CLI11's message for a bad command line (and its own exit code, e.g. 106, replaced by the
    // one usage code)
    (void)app.exit(e);
    return kExitUsage;
  } catch (const rigid::cli::UsageError& e) {
    // a bad option value found by a command (not by CLI11): the same status as CLI11's
    std::fprintf(stderr, "rigid: error: %s\n", rigid::word_for(rigid::Surface::kCli, e.what()).c_str());
    std::fputs("Run with --help for more information.\n", stderr);
    return kExitUsage;
  } catch (const rigid::Cancelled& e) {
    std::fprintf(stderr, "rigid: interrupted: %s\n", e.what());
    return kExitInterrupted;
  } catch (const rigid::Error& e) {
    // the library names its settings in its own terms; here they are flags
    std::fprintf(stderr, "rigid: error: %s\n", rigid::word_for(rigid::Surface::kCli, e.what()).c_str());
    return kExitRefused;
  } catch (const std::bad_alloc&) {
    std::fputs("rigid: error: out of memory; the input asks for more memory than is available (see "
               "--max-memory for runs)\n",
               stderr);
    return kExitRefused;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "rigid: error: %s\n", e.what());
    return kExitRefused;
  }
  return kExitOk;
}
