// Fuzz target: the STL reader (seeds: ASCII STL files) and the mesh-to-mass path on its output.
#include "mesh_fuzz.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  return rigid::fuzz::fuzz_mesh(data, size, &rigid::mesh::read_stl, "stl");
}
