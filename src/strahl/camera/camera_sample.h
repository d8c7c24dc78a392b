#pragma once
// What a pixel sampler hands the camera for one sample: where on the film (raster units, x to
// the right, y up from the bottom row, as Camera::generate_ray takes them), where on the lens
// (unit square; (0.5, 0.5) is the centre) and when in the shutter interval (0..1).

#include "strahl/math/vec2.h"

namespace strahl {

struct CameraSample {
  Real film_x = 0, film_y = 0;
  Vec2 lens{Real(0.5), Real(0.5)};
  Real time = 0;
};

}  // namespace strahl
