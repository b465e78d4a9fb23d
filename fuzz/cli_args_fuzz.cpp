// Fuzz target: the rigid command line (rigid::cli::command_line, apps/rigid/main.cpp): the input
// split at every NUL byte into the arguments after argv[0] "rigid" (an empty input is no argument;
// "a\0" is "a" and an empty one). Parsing only (Dispatch::kParseOnly): CLI11 with every
// subcommand's options and validators, the empty-argument rule, the misspelt-name and
// number-range checks (cli_suggest.hpp); no subcommand runs, so nothing is read or written. As
// a second safety net each input runs in an empty scratch directory made the current one, which
// must still be empty after it.
// Outcome: status 0 (parsed; --help, --version), 1 or 2 (refused, with a message that is checked
// as any refusal: not an internal error, no library's raw text); any other exception escapes
// command_line (it turns only rigid::Error and CLI11's into statuses when parsing only).
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <sstream>
#include <string>
#include <vector>

#include "command_line.hpp"
#include "fuzz_support.hpp"

namespace {

namespace fs = std::filesystem;

[[noreturn]] void fail(const std::string& what) {
  std::fprintf(stderr, "rigid fuzz: command line: %s\n", what.c_str());
  std::abort();
}

// `dir` is the current directory while this lives; the one before it is restored after
class InDirectory {
 public:
  explicit InDirectory(const fs::path& dir) : before_(fs::current_path()) { fs::current_path(dir); }
  ~InDirectory() { fs::current_path(before_); }
  InDirectory(const InDirectory&) = delete;
  InDirectory& operator=(const InDirectory&) = delete;

 private:
  fs::path before_;
};

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string_view input = rigid::fuzz::as_text(data, size);
  std::vector<std::string> args{"rigid"};
  for (std::size_t start = 0; size > 0;) {
    const std::size_t nul = input.find('\0', start);
    args.emplace_back(input.substr(start, nul - start));
    if (nul == std::string_view::npos) break;
    start = nul + 1;
  }
  std::vector<char*> argv;
  for (std::string& a : args) argv.push_back(a.data());
  argv.push_back(nullptr);

  static const fs::path cwd = [] {
    const fs::path d = rigid::fuzz::scratch_dir() / "cli_cwd";
    fs::create_directories(d);
    return d;
  }();
  if (!fs::is_empty(cwd)) fail("the scratch directory is not empty before the command line");
  std::ostringstream out;
  std::ostringstream err;
  int status = 0;
  {
    const InDirectory in(cwd);
    status = rigid::cli::command_line(static_cast<int>(args.size()), argv.data(), out, err,
                                      rigid::cli::Dispatch::kParseOnly);
  }
  if (!fs::is_empty(cwd)) fail("parsing wrote into the current directory");
  if (status != rigid::cli::kExitOk && status != rigid::cli::kExitRefused &&
      status != rigid::cli::kExitUsage) {
    fail("exit status " + std::to_string(status) + " (expected 0, 1 or 2)");
  }
  if (status != rigid::cli::kExitOk) {
    if (err.str().empty()) fail("refused without a message");
    rigid::fuzz::check_refusal(rigid::Error(err.str()), input);
  }
  return 0;
}
