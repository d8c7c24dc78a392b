#pragma once
// The lecture's search: every primitive is tested (n_x · n_y · n_o intersections). For checking
// the other structures and for tiny scenes.

#include <cstdint>

#include "strahl/accel/traversal.h"

namespace strahl {

struct NaiveView {
  std::uint32_t count = 0;
};

template <class Visitor>
STRAHL_HOST_DEVICE inline void traverse(const NaiveView& v, const Ray&, Real, Real& t_max, Visitor& visit) {
  for (std::uint32_t prim = 0; prim < v.count; ++prim)
    if (visit(prim, -kInfinity, kInfinity, t_max)) return;
}

}  // namespace strahl
