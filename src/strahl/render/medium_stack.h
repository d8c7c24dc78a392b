#pragma once
// The media a ray is travelling through, innermost on top, so that a refracted ray entering and
// leaving nested objects uses the right pair of indices n1, n2 in Snell's law.

#include "strahl/math/config.h"

namespace strahl {

struct MediumStack {
  static constexpr int kCapacity = 8;
  Real ior[kCapacity];
  int size = 1;

  STRAHL_HOST_DEVICE explicit MediumStack(Real outside) : ior{outside} {}

  STRAHL_HOST_DEVICE Real current() const { return ior[size - 1]; }
  // Index of the medium outside the current one (the scene's medium at the bottom).
  STRAHL_HOST_DEVICE Real outer() const { return size > 1 ? ior[size - 2] : ior[0]; }
  STRAHL_HOST_DEVICE MediumStack entered(Real n) const {
    MediumStack s = *this;
    if (s.size < kCapacity) s.ior[s.size++] = n; else s.ior[kCapacity - 1] = n;
    return s;
  }
  STRAHL_HOST_DEVICE MediumStack left() const {
    MediumStack s = *this;
    if (s.size > 1) --s.size;
    return s;
  }
};

}  // namespace strahl
