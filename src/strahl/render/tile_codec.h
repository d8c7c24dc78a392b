#pragma once
// TileWork as bytes: what an MPI master sends a worker (the request: which pixels, which
// samples, the film's sums carried in) and what comes back (the result: samples taken, the new
// sums, wide-filter contributions, ray counters); the resume journal stores results the same way.
// Little-endian fixed-width fields; sections that are all zero or uniform are marked instead of
// sent (a first pass carries no sums in; a uniform pass one sample range for all its pixels).

#include <cstdint>
#include <span>
#include <vector>

#include "strahl/render/tile.h"

namespace strahl {

enum class TilePart : std::uint8_t { Request, Result };

std::vector<std::uint8_t> encode_tile(const TileWork& work, TilePart part);
// Fills `work` from bytes made by encode_tile (a Result over a tile that has its request, or
// alone). Throws strahl::Error when the bytes are not a whole, consistent tile of that part.
void decode_tile(std::span<const std::uint8_t> bytes, TilePart part, TileWork& work);

}  // namespace strahl
