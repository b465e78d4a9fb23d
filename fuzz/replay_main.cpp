// Replays saved inputs through the fuzz targets without libFuzzer, in an ordinary build (g++,
// the `ci` preset): `rigid_fuzz_replay <target> <file or folder>...`. Each target's source is
// compiled here with LLVMFuzzerTestOneInput renamed to rigid_fuzz_<target>, so that one
// executable holds them all. The outcome rule is the targets' own (fuzz_support.hpp): a
// rigid::Error is a normal outcome, anything else ends the process with a failure, and so does
// an input that runs longer than the limit of the fuzz runs (10 s, or RIGID_FUZZ_TIMEOUT
// seconds): a hang. Each input is named on stderr before it runs, so a failure says which
// file it was.
#include <algorithm>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <string>
#include <vector>

#include <csignal>
#include <unistd.h>

#define RIGID_FUZZ_TARGET(name) \
  extern "C" int rigid_fuzz_##name(const std::uint8_t* data, std::size_t size);
#include "targets.def"
#undef RIGID_FUZZ_TARGET

namespace {

using Target = int (*)(const std::uint8_t*, std::size_t);

const std::map<std::string, Target>& targets() {
  static const std::map<std::string, Target> table{
#define RIGID_FUZZ_TARGET(name) {#name, &rigid_fuzz_##name},
#include "targets.def"
#undef RIGID_FUZZ_TARGET
  };
  return table;
}

extern "C" void on_timeout(int) {
  static const char kMessage[] = "rigid_fuzz_replay: the input above ran past the time limit (a hang)\n";
  (void)!::write(2, kMessage, sizeof kMessage - 1);
  ::_exit(3);
}

std::vector<std::filesystem::path> inputs(const std::filesystem::path& arg) {
  std::vector<std::filesystem::path> files;
  if (std::filesystem::is_directory(arg)) {
    for (const auto& e : std::filesystem::directory_iterator(arg)) {
      if (e.is_regular_file() && e.path().filename().string().front() != '.') files.push_back(e.path());
    }
    std::sort(files.begin(), files.end());
  } else {
    files.push_back(arg);
  }
  return files;
}

}  // namespace

int main(int argc, char** argv) {
  if (argc < 3 || targets().count(argv[1]) == 0) {
    std::fprintf(stderr, "usage: %s <target> <file or folder>...\ntargets:", argv[0]);
    for (const auto& [name, f] : targets()) std::fprintf(stderr, " %s", name.c_str());
    std::fprintf(stderr, "\n");
    return 2;
  }
  const Target target = targets().at(argv[1]);
  const char* limit_env = std::getenv("RIGID_FUZZ_TIMEOUT");
  const unsigned limit = limit_env != nullptr ? static_cast<unsigned>(std::atoi(limit_env)) : 10u;
  std::signal(SIGALRM, on_timeout);
  std::size_t count = 0;
  for (int i = 2; i < argc; ++i) {
    if (!std::filesystem::exists(argv[i])) {
      std::fprintf(stderr, "%s: no such file or folder\n", argv[i]);
      return 2;
    }
    for (const auto& file : inputs(argv[i])) {
      std::string data(std::filesystem::file_size(file), '\0');
      std::ifstream in(file, std::ios::binary);
      if (!in.read(data.data(), static_cast<std::streamsize>(data.size()))) {
        std::fprintf(stderr, "%s: cannot read\n", file.c_str());
        return 2;
      }
      std::fprintf(stderr, "%s: %s (%zu bytes)\n", argv[1], file.c_str(), data.size());
      ::alarm(limit);
      target(reinterpret_cast<const std::uint8_t*>(data.data()), data.size());
      ::alarm(0);
      ++count;
    }
  }
  std::printf("%s: %zu inputs replayed, all accepted or refused with a rigid::Error\n", argv[1], count);
  return 0;
}
