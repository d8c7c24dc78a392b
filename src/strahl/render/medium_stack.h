#pragma once
// The media a ray is travelling through, innermost on top, so that a refracted ray entering and
// leaving nested objects uses the right pair of indices n1, n2 in Snell's law.

#include "strahl/math/config.h"

namespace strahl {

struct MediumStack {
  static constexpr int kCapacity = 8;
  Real ior[kCapacity];
  int size = 1;

  // What enter() or leave() changed: the one slot they may overwrite, and the size.
  struct Undo {
    Real slot;
    int size;
  };

  STRAHL_HOST_DEVICE explicit MediumStack(Real outside) : ior{outside} {}

  STRAHL_HOST_DEVICE Real current() const { return ior[size - 1]; }
  // Index of the medium outside the current one (the scene's medium at the bottom).
  STRAHL_HOST_DEVICE Real outer() const { return size > 1 ? ior[size - 2] : ior[0]; }

  // In place, for the iterative integrator (render/whitted.h), which keeps one stack for the path
  // it is on: entering medium n pushes it (a full stack replaces its innermost medium), leaving
  // pops one (never the scene's medium). undo() puts back exactly what either changed, so
  // undoing in reverse order restores every earlier state, slots above the size included.
  STRAHL_HOST_DEVICE Undo enter(Real n) {
    const Undo u = undo_record();
    if (size < kCapacity) ior[size++] = n; else ior[kCapacity - 1] = n;
    return u;
  }
  STRAHL_HOST_DEVICE Undo leave() {
    const Undo u = undo_record();
    if (size > 1) --size;
    return u;
  }
  STRAHL_HOST_DEVICE void undo(const Undo& u) {
    size = u.size;
    ior[slot_written(u.size)] = u.slot;
  }

 private:
  // The only slot enter() writes at a given size (leave() writes none).
  STRAHL_HOST_DEVICE static int slot_written(int n) { return n < kCapacity ? n : kCapacity - 1; }
  STRAHL_HOST_DEVICE Undo undo_record() const { return Undo{ior[slot_written(size)], size}; }
};

}  // namespace strahl
