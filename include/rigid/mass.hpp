#pragma once

/// The mass module: mass properties (3D, 2D, n-D), primitives, density cubature.
#include "rigid/mass/density.hpp"
#include "rigid/mass/mass_properties.hpp"
#include "rigid/mass/mass_properties2.hpp"
#include "rigid/mass/placement.hpp"
#include "rigid/mass/primitive_table.hpp"
#include "rigid/mass/pseudo_inertia.hpp"
#include "rigid/mass/primitives.hpp"
#include "rigid/mass/second_moments.hpp"
#include "rigid/mass/uncertainty.hpp"
