#include "rigid/lagrange/system.hpp"
