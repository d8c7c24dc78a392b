#pragma once
// A point of the unit square (sample values, lens and film offsets).

#include "strahl/math/config.h"

namespace strahl {

struct Vec2 {
  Real x = 0, y = 0;
};

}  // namespace strahl
