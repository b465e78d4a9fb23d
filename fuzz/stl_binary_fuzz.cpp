// Fuzz target: the STL reader (seeds: binary STL files, including headers that start with "solid") and the mesh-to-mass path on its output.
#include "mesh_fuzz.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  return rigid::fuzz::fuzz_mesh(data, size, &rigid::mesh::read_stl, "stl");
}
