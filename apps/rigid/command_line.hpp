#pragma once
// The rigid command line as a function (defined in main.cpp, the one translation unit that sees
// CLI11): the `rigid` executable calls it from program.cpp, and the cli_args fuzz target
// (fuzz/cli_args_fuzz.cpp) calls it with Dispatch::kParseOnly.
#include <ostream>

namespace rigid::cli {

/// What command_line does once the arguments are parsed.
enum class Dispatch {
  kRun,        ///< run the subcommand (the `rigid` executable)
  kParseOnly,  ///< stop after parsing and validating the arguments: no subcommand runs, so no
               ///< file is read or written; an exception that is neither a rigid::Error nor
               ///< CLI11's propagates instead of becoming status 1
};

/// Exit statuses of every subcommand (documented in the --help footer, README and
/// docs/reliability.md).
inline constexpr int kExitOk = 0;
inline constexpr int kExitRefused = 1;  ///< a rigid::Error: the input was refused with a reason
inline constexpr int kExitUsage = 2;    ///< the command line itself is wrong
inline constexpr int kExitInterrupted = 130;  ///< Ctrl-C (the shell's 128 + SIGINT)

/// Parses argv (argv[0] is the program; argv[argc] need not be null) and runs the subcommand:
/// help and version on `out`, every message of a refusal on `err`. Returns the exit status.
int command_line(int argc, char** argv, std::ostream& out, std::ostream& err,
                 Dispatch dispatch = Dispatch::kRun);

}  // namespace rigid::cli
