#pragma once

/// The mesh module: triangle meshes, readers, repair and exact mass properties.
#include "rigid/mesh/fill_holes.hpp"
#include "rigid/mesh/mass_from_file.hpp"
#include "rigid/mesh/mesh_mass.hpp"
#include "rigid/mesh/mesh_uncertainty.hpp"
#include "rigid/mesh/read_mesh.hpp"
#include "rigid/mesh/repair.hpp"
#include "rigid/mesh/triangle_mesh.hpp"
