#include <gtest/gtest.h>

#include "strahl/render/render_scene.h"
#include "strahl/render/renderer.h"
#include "strahl/scene/scene.h"

TEST(Smoke, LectureSceneRenders) {
  strahl::Scene scene = strahl::lecture_scene();
  scene.settings.width = 32;
  scene.settings.height = 18;
  const strahl::Image image = strahl::render(strahl::compile(scene), {});
  EXPECT_EQ(image.width(), 32);
}
