#include "strahl/render/aov.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

namespace strahl {

AovImages render_aovs(const RenderScene& scene, int threads) {
  const SceneView view = scene.view();
  const int w = view.camera.nx, h = view.camera.ny;
  AovImages out{Image(w, h), Image(w, h), Image(w, h), Image(w, h)};
  const auto rgb = [](const Vec3& v) { return Rgb{float(v.x), float(v.y), float(v.z)}; };
  tbb::task_arena arena(threads > 0 ? threads : tbb::task_arena::automatic);
  arena.execute([&] {
    tbb::parallel_for(tbb::blocked_range<int>(0, h), [&](const tbb::blocked_range<int>& rows) {
      for (int row = rows.begin(); row != rows.end(); ++row)
        for (int x = 0; x < w; ++x) {
          const AovSample a = aov_sample(view, x, row);
          out.depth.at(x, row) = rgb(Vec3(a.depth));
          out.normal.at(x, row) = rgb(a.normal);
          out.albedo.at(x, row) = rgb(a.albedo);
          out.id.at(x, row) = rgb(Vec3(a.id));
        }
    });
  });
  return out;
}

}  // namespace strahl
