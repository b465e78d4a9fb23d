// The rigid command line: CLI11 parsing and the single error exit path (command_line.hpp; main()
// is in program.cpp, so that the cli_args fuzz target can parse command lines too).
#include <exception>
#include <new>
#include <ostream>

#include <CLI/CLI.hpp>
#include <fmt/format.h>

#include "cli_error.hpp"
#include "command_line.hpp"
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

namespace rigid::cli {
namespace {

// Thrown when Dispatch::kParseOnly stops command_line after parsing, before any subcommand's
// callback (its work) runs.
struct ParsedOnly {};

}  // namespace

int command_line(int argc, char** argv, std::ostream& out, std::ostream& err, Dispatch dispatch) {
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
  // CLI11 calls the root's parse-complete callback when every argument is parsed and validated,
  // before the subcommands' callbacks: parsing only ends there (the callbacks stay, since they
  // own the options' storage)
  if (dispatch == Dispatch::kParseOnly) app.parse_complete_callback([] { throw ParsedOnly{}; });

  // One rule for empty arguments, before CLI11 sees them (an empty positional followed by an
  // option sent its parser into an endless loop): no argument of rigid may be empty.
  for (int i = 1; i < argc; ++i) {
    if (argv[i][0] == '\0') {
      err << fmt::format(
          "rigid: error: argument {} is empty{}{}{}; every argument needs a value (a file, a "
          "number, a name): remove it or give one\n",
          i, i > 1 ? " (after '" : "", i > 1 ? argv[i - 1] : "", i > 1 ? "')" : "");
      return kExitUsage;
    }
  }
  try {
    rigid::cli::refuse_misspelt_names(app, argc, argv);
    try {
      app.parse(argc, argv);
    } catch (const ParsedOnly&) {
      // parsed and validated: the subcommand is not run
    }
    if (app.get_subcommands().empty()) {
      err << app.help() << "rigid: error: a subcommand is required (see the list above)\n";
      return kExitUsage;
    }
  } catch (const CLI::CallForHelp& e) {
    return app.exit(e, out, err);  // --help: the text on `out`, 0
  } catch (const CLI::CallForAllHelp& e) {
    return app.exit(e, out, err);
  } catch (const CLI::CallForVersion& e) {
    return app.exit(e, out, err);
  } catch (const CLI::ParseError& e) {
    // CLI11's message for a bad command line (and its own exit code, e.g. 106, replaced by the
    // one usage code)
    (void)app.exit(e, out, err);
    return kExitUsage;
  } catch (const rigid::cli::UsageError& e) {
    // a bad option value found by a command (not by CLI11): the same status as CLI11's
    err << "rigid: error: " << word_for(Surface::kCli, e.what())
        << "\nRun with --help for more information.\n";
    return kExitUsage;
  } catch (const rigid::Cancelled& e) {
    err << "rigid: interrupted: " << e.what() << "\n";
    return kExitInterrupted;
  } catch (const rigid::Error& e) {
    // the library names its settings in its own terms; here they are flags
    err << "rigid: error: " << word_for(Surface::kCli, e.what()) << "\n";
    return kExitRefused;
  } catch (const std::bad_alloc&) {
    if (dispatch == Dispatch::kParseOnly) throw;
    err << "rigid: error: out of memory; the input asks for more memory than is available (see "
           "--max-memory for runs)\n";
    return kExitRefused;
  } catch (const std::exception& e) {
    if (dispatch == Dispatch::kParseOnly) throw;
    err << "rigid: error: " << e.what() << "\n";
    return kExitRefused;
  }
  return kExitOk;
}

}  // namespace rigid::cli
