#pragma once

#include "rigid/common/error.hpp"
#include "rigid/common/format.hpp"
#include "rigid/common/scalars.hpp"
