#pragma once

/// Scene files: a whole simulation from one TOML file, parsed with file:line:col errors and
/// turned into a model that runs (docs/scene-format.md).
#include "rigid/scene/model.hpp"
#include "rigid/scene/modes.hpp"
#include "rigid/scene/scene.hpp"
