// Build-time generator of the lagrange benchmark: writes the exported C++ of the N-link chain
// (rigid::lagrange::emit_cpp) to DIR/chainN.hpp, namespace chainN, for each N given.
//   rigid_lagrange_emit_chains DIR N...
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <string>

#include "lagrange_chain.hpp"
#include "rigid/lagrange/export.hpp"

int main(int argc, char** argv) {
  if (argc < 3) {
    std::fprintf(stderr, "usage: rigid_lagrange_emit_chains DIR N...\n");
    return 2;
  }
  for (int k = 2; k < argc; ++k) {
    const int n = std::atoi(argv[k]);
    const rigid::lagrange::System sys(rigid::bench::chain_spec(n));
    rigid::lagrange::ExportOptions options;
    options.name = fmt::format("chain{}", n);
    options.source = fmt::format("the {}-link chain of bench/lagrange_chain.hpp", n);
    const std::string path = fmt::format("{}/chain{}.hpp", argv[1], n);
    std::ofstream out(path, std::ios::binary);
    out << rigid::lagrange::emit_cpp(sys, options);
    if (!out) {
      std::fprintf(stderr, "rigid_lagrange_emit_chains: cannot write %s\n", path.c_str());
      return 1;
    }
  }
  return 0;
}
