#pragma once
// The CPU's tile worker: every sample a TileWork asks for, through the integrator, into the tile's
// film buffers. Used by the CPU back end's threads and by MPI workers alike.

#include "strahl/render/film.h"
#include "strahl/render/scene_view.h"
#include "strahl/render/stop_token.h"
#include "strahl/render/tile.h"
#include "strahl/sampling/pixel_sampler.h"

namespace strahl {

// Renders the samples `work` asks for (its buffers sized by FilmLayout::prepare or
// Film::begin_tile). A pixel's samples go through the packet front end (render/packet_radiance.h)
// in packets of up to 16 where it handles the scene, else one by one; pixels of a row that take
// one sample each go in packets of up to 16 neighbours. Stops between two samples or packets when
// `stop` is requested; work.taken then says how far each pixel got.
void render_tile(const SceneView& view, const PixelSampler& sampler, const FilmLayout& film, const StopToken& stop,
                 TileWork& work);

}  // namespace strahl
