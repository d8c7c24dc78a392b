// The lecture's scene, written exactly as on its first slide, rendered to lecture-api.png.
//   build/bin/lecture [output.png]
// Built twice: inside strahl's build (examples/CMakeLists.txt), and as the out-of-tree project
// beside it, against an installed strahl (CMakeLists.txt here; docs/library.md).

#include <cstdio>
#include <memory>

#include "strahl/strahl.h"

using namespace strahl;

int main(int argc, char** argv) {
  Scene* scene = new Scene();
  scene->addSceneObject(new Plane(Vec3(0.0, 1.0, 0.0), 0.0, Vec3(0.3, 0.3, 0.3)));
  scene->addSceneObject(new Sphere(Vec3(0.05, 0.3, 0.0), 0.3, Vec3(0.8, 0.2, 0.2)));
  scene->addSceneObject(new Sphere(Vec3(0.4, 0.1, 0.1), 0.1, Vec3(0.0, 1.0, 0.0)));
  scene->addSceneObject(new Sphere(Vec3(-0.35, 0.25, -0.15), 0.25, Vec3(0.5, 0.5, 0.1)));
  scene->addSceneObject(new Sphere(Vec3(-0.35, 0.15, 0.3), 0.15, Vec3(0.0, 0.0, 1.0)));
  scene->addSceneObject(new Sphere(Vec3(0.15, 0.6, -1.0), 0.6, Vec3(0.2, 0.4, 0.5)));
  scene->addLightSource(Vec3(1.0, 1.5, 1.0));

  // The default camera is the benchmark's: eye (0, 0.8, 2.2), look-at (0, 0.25, 0), 50° across.
  scene->settings.width = 800;
  scene->settings.height = 450;

  const std::unique_ptr<Scene> owned(scene);
  try {
    const Image image = render(compile(*owned), RenderOptions{});
    write_image(image, argc > 1 ? argv[1] : "lecture-api.png");
  } catch (const Error& e) {
    std::fprintf(stderr, "lecture: %s\n", e.what());
    return 2;
  }
  return 0;
}
