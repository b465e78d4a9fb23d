#pragma once

#include "rigid/common/did_you_mean.hpp"
#include "rigid/common/error.hpp"
#include "rigid/common/format.hpp"
#include "rigid/common/scalars.hpp"
#include "rigid/common/wording.hpp"
