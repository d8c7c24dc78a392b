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

// The film positions and shutter times of a packet of N camera samples, one array per
// coordinate, for the camera's rays with the lanes side by side (Camera::directions). The
// samplers' lane loops fill them as they fill the CameraSamples, so that no lane's value is
// stored alone and read back four at a time (a store-forwarding stall per load).
template <int N>
struct FilmLanes {
  Real x[N], y[N], time[N];

  // The lanes of cs[0 … count − 1] (1 ≤ count ≤ N), padded.
  STRAHL_HOST_DEVICE void set(const CameraSample* cs, int count) {
    for (int i = 0; i < count; ++i) x[i] = cs[i].film_x, y[i] = cs[i].film_y, time[i] = cs[i].time;
    pad(count);
  }
  // cs[0 … N) from the lanes, as a sampler without lens and shutter makes them (lens (0.5, 0.5)).
  STRAHL_HOST_DEVICE void get(CameraSample* cs) const {
    for (int i = 0; i < N; ++i) {
      cs[i].film_x = x[i];
      cs[i].film_y = y[i];
      cs[i].lens = Vec2{Real(0.5), Real(0.5)};
      cs[i].time = time[i];
    }
  }
  // The lanes from `count` on get lane 0's values (nobody reads them).
  STRAHL_HOST_DEVICE void pad(int count) {
    for (int i = count; i < N; ++i) x[i] = x[0], y[i] = y[0], time[i] = time[0];
  }
};

}  // namespace strahl
