#pragma once

/// The mesh targets: one format's reader on the input (written to a scratch file, since the
/// readers take a path), then the whole file-to-mass path on the same file (repair, hole
/// filling, solid and shell mass properties), as the CLI, scenes and Python use it.

#include <optional>
#include <string>

#include "fuzz_support.hpp"
#include "rigid/mesh.hpp"

namespace rigid::fuzz {

using MeshReader = mesh::TriangleMesh (*)(const std::string&, double);

inline int fuzz_mesh(const std::uint8_t* data, std::size_t size, MeshReader reader,
                     const char* extension) {
  const std::string_view input = as_text(data, size);
  const std::string path = write_scratch(data, size, std::string("input.") + extension);
  refuse_or_return(input, [&] { (void)reader(path, 1.0); });
  const mesh::MassSpec solid{std::nullopt, 1.0, false, std::nullopt};
  const mesh::MassSpec shell{std::nullopt, 1.0, true, std::nullopt};
  refuse_or_return(input, [&] { (void)mesh::mesh_mass_from_file(path, 1.0, solid, {}, true); });
  refuse_or_return(input, [&] { (void)mesh::mesh_mass_from_file(path, 0.001, shell); });
  return 0;
}

}  // namespace rigid::fuzz
