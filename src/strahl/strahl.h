#pragma once
// Everything a program using strahl as a library needs: the scene API, compile(), render() and
// image output, and the version (strahl/version.h). These headers, and the ones they include, are
// what `cmake --install` installs (docs/library.md); every other header is internal.

#include "strahl/image/image_io.h"
#include "strahl/render/render_scene.h"
#include "strahl/render/renderer.h"
#include "strahl/scene/scene.h"
#include "strahl/scene/scene_file.h"
#include "strahl/scene/scene_writer.h"
#include "strahl/scene/csg.h"
#include "strahl/scene/solids.h"
#include "strahl/version.h"
