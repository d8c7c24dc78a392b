// strahl-view's parts that need no window (apps/strahl-view): the camera controls' maths, the
// printed camera YAML, scripts, the font, numbered saving, the display mapping, file watching,
// and the view renderer against render().

#include <gtest/gtest.h>

#include <random>
#include <thread>

#include "camera_control.h"
#include "camera_yaml.h"
#include "device_backend.h"
#include "display.h"
#include "save.h"
#include "scene_source.h"
#include "script.h"
#include "strahl/image/image_io.h"
#include "strahl/render/cpu_backend.h"
#include "strahl/scene/camera_build.h"
#include "strahl/scene/scene_file.h"
#include "test_helpers.h"
#include "text.h"
#include "view_renderer.h"

namespace strahl::view_test {
namespace {

using view::ViewAxes;

// Cameras at random places looking at random points, with random up vectors and fields of view.
std::vector<CameraDescription> random_cameras(int n) {
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> u(-10, 10), fov(5, 120);
  std::vector<CameraDescription> out;
  while (int(out.size()) < n) {
    CameraDescription c;
    c.position = Vec3(u(rng), u(rng), u(rng));
    c.look_at = Vec3(u(rng), u(rng), u(rng));
    c.up = Vec3(u(rng), u(rng), u(rng));
    c.fov_degrees = fov(rng);
    const Vec3 view = c.look_at - c.position;
    if (length(view) < 0.1 || length(cross(normalize(view), normalize(c.up))) < 0.2) continue;
    out.push_back(c);
  }
  return out;
}

Real angle_to_up(const CameraDescription& c) {
  return std::acos(std::clamp(dot(normalize(c.position - c.look_at), normalize(c.up)), Real(-1), Real(1)));
}

TEST(ViewControls, OrbitKeepsTheDistanceToLookAt) {
  std::mt19937_64 rng(1);
  std::uniform_real_distribution<double> angle(-3, 3);
  for (CameraDescription c : random_cameras(200)) {
    const Real d = view::distance_to_look_at(c);
    const Vec3 look_at = c.look_at;
    for (int i = 0; i < 20; ++i) {
      view::orbit(c, angle(rng), angle(rng));
      EXPECT_NEAR(view::distance_to_look_at(c), d, 1e-12 * d);
      EXPECT_EQ(c.look_at, look_at);
      const Real a = angle_to_up(c);  // never over the pole
      EXPECT_GE(a, view::kMinPoleAngle - 1e-9);
      EXPECT_LE(a, kPi - view::kMinPoleAngle + 1e-9);
      EXPECT_NO_THROW(build_camera(c, 16, 9));
    }
  }
}

TEST(ViewControls, YawTurnsAboutUpAndAFullTurnComesBack) {
  for (CameraDescription c : random_cameras(50)) {
    if (angle_to_up(c) < view::kMinPoleAngle || angle_to_up(c) > kPi - view::kMinPoleAngle) continue;
    const CameraDescription start = c;
    const Vec3 up = normalize(c.up);
    view::orbit(c, 0.7, 0);  // yaw alone: the height along up stays
    EXPECT_NEAR(dot(c.position - c.look_at, up), dot(start.position - start.look_at, up), 1e-9);
    const Vec3 a = start.position - start.look_at, b = c.position - c.look_at;
    const Vec3 ha = a - up * dot(a, up), hb = b - up * dot(b, up);
    EXPECT_NEAR(std::acos(std::clamp(dot(normalize(ha), normalize(hb)), Real(-1), Real(1))), 0.7, 1e-9);
    EXPECT_GT(dot(cross(ha, hb), up), 0);  // counter-clockwise seen from above
    for (int i = 0; i < 9; ++i) view::orbit(c, (2 * kPi - 0.7) / 9, 0);
    EXPECT_VEC_NEAR(c.position, start.position, 1e-9 * view::distance_to_look_at(c));
  }
}

TEST(ViewControls, PitchRaisesTheEyeAndStopsShortOfThePole) {
  CameraDescription c;  // the lecture's camera
  const Real before = angle_to_up(c);
  view::orbit(c, 0, 0.2);
  EXPECT_NEAR(angle_to_up(c), before - 0.2, 1e-12);
  view::orbit(c, 0, 10);  // far past the pole
  EXPECT_NEAR(angle_to_up(c), view::kMinPoleAngle, 1e-12);
  view::orbit(c, 0, -10);
  EXPECT_NEAR(angle_to_up(c), kPi - view::kMinPoleAngle, 1e-12);
}

TEST(ViewControls, PanMovesEyeAndLookAtTogether) {
  std::mt19937_64 rng(2);
  std::uniform_real_distribution<double> shift(-2, 2);
  for (CameraDescription c : random_cameras(200)) {
    const CameraDescription start = c;
    const ViewAxes before = view::view_axes(c);
    const Real dx = shift(rng), dy = shift(rng), d = view::distance_to_look_at(c);
    view::pan(c, dx, dy);
    const Vec3 moved_eye = c.position - start.position, moved_target = c.look_at - start.look_at;
    EXPECT_VEC_NEAR(moved_eye, moved_target, 1e-12 * (1 + d));
    EXPECT_VEC_NEAR(moved_eye, (before.u * dx + before.v * dy) * d, 1e-9 * (1 + d));
    EXPECT_NEAR(view::distance_to_look_at(c), d, 1e-9 * d);
    const ViewAxes after = view::view_axes(c);  // the view direction stays
    EXPECT_VEC_NEAR(after.w, before.w, 1e-9);
    EXPECT_VEC_NEAR(after.u, before.u, 1e-9);
  }
}

TEST(ViewControls, DollyMovesTheEyeAlongTheViewDirection) {
  for (CameraDescription c : random_cameras(100)) {
    const CameraDescription start = c;
    const Real d = view::distance_to_look_at(c);
    view::dolly(c, 0.5);
    EXPECT_NEAR(view::distance_to_look_at(c), d * 0.5, 1e-12 * d);
    EXPECT_EQ(c.look_at, start.look_at);
    EXPECT_VEC_NEAR(view::view_axes(c).w, view::view_axes(start).w, 1e-12);
    view::dolly(c, 1e-30);
    EXPECT_NEAR(view::distance_to_look_at(c), view::kMinDistance, 1e-15);
    EXPECT_NO_THROW(build_camera(c, 16, 9));
  }
}

TEST(ViewControls, FlyMovesBothAlongTheCameraAxes) {
  for (CameraDescription c : random_cameras(100)) {
    const CameraDescription start = c;
    const ViewAxes a = view::view_axes(c);
    view::fly(c, 0.25, -0.5, 2);
    const Vec3 expected = a.u * 0.25 - normalize(start.up) * 0.5 - a.w * 2;
    EXPECT_VEC_NEAR(c.position - start.position, expected, 1e-12 * 20);
    EXPECT_VEC_NEAR(c.look_at - start.look_at, expected, 1e-12 * 20);
  }
}

TEST(ViewControls, ZoomScalesTheFieldOfViewWithinItsLimits) {
  CameraDescription c;
  view::zoom(c, 0.5);
  EXPECT_DOUBLE_EQ(c.fov_degrees, 25);
  view::zoom(c, 1e-9);
  EXPECT_DOUBLE_EQ(c.fov_degrees, view::kMinFov);
  view::zoom(c, 1e9);
  EXPECT_DOUBLE_EQ(c.fov_degrees, view::kMaxFov);
  CameraDescription e;
  e.explicit_image_plane = true;
  e.l = -1; e.r = 3; e.b = -1; e.t = 1;
  view::zoom(e, 0.5);  // about the centre (1, 0)
  EXPECT_DOUBLE_EQ(e.l, 0);
  EXPECT_DOUBLE_EQ(e.r, 2);
  EXPECT_DOUBLE_EQ(e.b, -0.5);
  EXPECT_DOUBLE_EQ(e.t, 0.5);
}

TEST(ViewControls, FocusLooksAtThePointAndALensFocusesThere) {
  CameraDescription c;
  c.aperture = 0.1;
  c.focus_distance = 7;
  const Vec3 p(0.3, 0.1, -0.5);
  view::focus_on(c, p);
  EXPECT_EQ(c.look_at, p);
  const Camera cam = build_camera(c, 32, 18);
  EXPECT_NEAR(cam.focus_distance, length(p - c.position), 1e-12);
  // The centre pixel's ray goes through the point.
  const Ray r = cam.generate_ray(16, 9);
  EXPECT_VEC_NEAR(normalize(r.direction), normalize(p - c.position), 1e-12);
  const CameraDescription before = c;
  view::focus_on(c, c.position);  // at the eye: nothing
  EXPECT_EQ(c.look_at, before.look_at);
}

// The printed block, pasted into a scene, gives the very same camera (every bit).
TEST(ViewCameraYaml, RoundTripsExactly) {
  int n = 0;
  for (CameraDescription c : random_cameras(100)) {
    if (n % 3 == 1) {
      c.aperture = 0.05 * n;
      c.focus_distance = 1.0 / 3 + n;
    }
    if (n % 5 == 2) c.fov_axis = CameraDescription::FovAxis::Vertical;
    if (n % 7 == 3) {
      c.explicit_image_plane = true;
      c.l = -0.1 * n; c.r = 1.0 / 7; c.b = -0.3; c.t = 0.2 / 3; c.d = 1.1;
    }
    if (n % 4 == 0) {
      c.shutter_open = 0.125;
      c.shutter_close = 2.0 / 3;
    }
    ++n;
    const std::string text = view::camera_yaml(c) + "objects:\n  - {type: sphere, center: [0, 0, 0], radius: 1}\n";
    const Scene s = parse_scene(text, "pasted.yaml", ".");
    const CameraDescription& d = s.camera;
    EXPECT_EQ(d.position, c.position) << text;
    EXPECT_EQ(d.look_at, c.look_at);
    EXPECT_EQ(d.up, c.up);
    EXPECT_EQ(d.explicit_image_plane, c.explicit_image_plane);
    const Camera a = build_camera(c, 40, 30), b = build_camera(d, 40, 30);
    EXPECT_EQ(a.eye, b.eye);
    EXPECT_EQ(a.basis.u, b.basis.u);
    EXPECT_EQ(a.basis.v, b.basis.v);
    EXPECT_EQ(a.basis.w, b.basis.w);
    EXPECT_EQ(a.l, b.l);
    EXPECT_EQ(a.r, b.r);
    EXPECT_EQ(a.b, b.b);
    EXPECT_EQ(a.t, b.t);
    EXPECT_EQ(a.d, b.d);
    EXPECT_EQ(a.lens_radius, b.lens_radius);
    EXPECT_EQ(a.focus_distance, b.focus_distance);
    EXPECT_EQ(a.shutter_open, b.shutter_open);
    EXPECT_EQ(a.shutter_close, b.shutter_close);
  }
}

TEST(ViewScript, ParsesEveryEvent) {
  const auto e = view::parse_script(
      "# a comment\n"
      "0.5 mouse down left 10 20\n"
      "0 mouse move 11 21  # dragging\n"
      "\n"
      "0.25 mouse up right 12 22\n"
      "1 wheel -3\n"
      "0 key ctrl+shift+s\n"
      "0 key +\n"
      "0 keydown w\n"
      "2 keyup w\n"
      "0 wait spp 16\n"
      "0 wait still\n"
      "0 wait reload 2\n"
      "0 quit\n",
      "s.txt");
  using K = view::ScriptEvent::Kind;
  ASSERT_EQ(e.size(), 12u);
  EXPECT_EQ(e[0].kind, K::MouseDown);
  EXPECT_EQ(e[0].delay, 0.5);
  EXPECT_EQ(e[0].button, 1);
  EXPECT_EQ(e[0].x, 10);
  EXPECT_EQ(e[0].y, 20);
  EXPECT_EQ(e[1].kind, K::MouseMove);
  EXPECT_EQ(e[2].button, 3);
  EXPECT_EQ(e[2].line, 5);
  EXPECT_EQ(e[3].amount, -3);
  EXPECT_TRUE(e[4].ctrl && e[4].shift);
  EXPECT_EQ(e[4].key, "s");
  EXPECT_EQ(e[5].key, "+");
  EXPECT_EQ(e[6].kind, K::KeyDown);
  EXPECT_EQ(e[7].delay, 2);
  EXPECT_EQ(e[8].kind, K::WaitSpp);
  EXPECT_EQ(e[8].amount, 16);
  EXPECT_EQ(e[9].kind, K::WaitStill);
  EXPECT_EQ(e[10].kind, K::WaitReload);
  EXPECT_EQ(e[11].kind, K::Quit);
}

TEST(ViewScript, ErrorsNameLineAndColumn) {
  const std::pair<const char*, const char*> cases[] = {
      {"0 jump\n", "s.txt:1:3: unknown event 'jump'"},
      {"\n\nx quit\n", "s.txt:3:1: the delay must be"},
      {"-1 quit\n", "s.txt:1:1: the delay must be"},
      {"0 mouse down left 10\n", "s.txt:1:19: missing y"},
      {"0 mouse down top 1 2\n", "s.txt:1:14: the button must be"},
      {"0 mouse move 1 2.5\n", "s.txt:1:16: y must be a whole number"},
      {"0 wait spp 0\n", "s.txt:1:12: the count must be at least 1"},
      {"0 wait forever\n", "s.txt:1:8: wait for spp N"},
      {"0 quit now\n", "s.txt:1:8: unexpected 'now'"},
  };
  for (const auto& [text, message] : cases) {
    try {
      view::parse_script(text, "s.txt");
      ADD_FAILURE() << "no error for " << text;
    } catch (const Error& e) {
      EXPECT_NE(std::string(e.what()).find(message), std::string::npos) << e.what();
    }
  }
  EXPECT_THROW(view::load_script("/nonexistent/script.txt"), Error);
}

TEST(ViewText, EveryGlyphIsDistinctAndDrawn) {
  std::set<std::string> seen;
  for (char c = ' '; c <= '~'; ++c) {
    std::string bits;
    for (int row = 0; row < 7; ++row)
      for (int col = 0; col < 5; ++col) bits += view::glyph_pixel(c, col, row) ? '#' : '.';
    EXPECT_TRUE(seen.insert(bits).second) << "glyph of '" << c << "' repeats another";
    EXPECT_EQ(bits.find('#') == std::string::npos, c == ' ') << c;
  }
  view::Canvas canvas(20, 10);
  canvas.text(1, 1, "I", {255, 0, 0, 255});
  // 'I' is ".###." on top: pixels 2..4 of row 1.
  EXPECT_EQ(canvas.at(1, 1).a, 0);
  EXPECT_EQ(canvas.at(2, 1).r, 255);
  EXPECT_EQ(canvas.at(4, 1).r, 255);
  EXPECT_EQ(canvas.at(5, 1).a, 0);
  const view::Canvas box = view::text_box({"ab", "abcd"}, {255, 255, 255, 255});
  EXPECT_EQ(box.width(), 4 * view::kGlyphWidth + 12);
  EXPECT_EQ(box.height(), 2 * view::kGlyphHeight + 12);
}

TEST(ViewSave, NumbersTheFilesAndNeverOverwrites) {
  test::TempDir dir;
  Image image(3, 2);
  image.at(1, 1) = {0.25f, 0.5f, 1};
  const fs::path base = dir / "shot.pfm";
  test::write_text(dir / "shot-0001.pfm", "precious");
  const fs::path first = view::save_numbered(image, base, {});
  EXPECT_EQ(first, dir / "shot-0002.pfm");
  EXPECT_EQ(test::read_text(dir / "shot-0001.pfm"), "precious");
  EXPECT_EQ(read_image(first), image);
  EXPECT_EQ(view::save_numbered(image, base, {}), dir / "shot-0003.pfm");
  int files = 0;
  for (const auto& e : fs::directory_iterator(dir.path())) files += e.is_regular_file() ? 1 : 0;
  EXPECT_EQ(files, 3);  // no temporary file left behind
  EXPECT_THROW(view::save_numbered(image, dir / "missing" / "shot.png", {}), Error);
}

TEST(ViewDisplay, ExposureAndSrgbMatchTheWriters) {
  Image image(4, 1);
  image.at(0, 0) = {0.5f, 0.25f, 0.0f};
  image.at(1, 0) = {2.0f, -1.0f, 1.0f};
  image.at(2, 0) = {0.001f, 0.9f, 0.04f};
  view::Rgba8Image out;
  view::to_display(image, view::Display::Beauty, 0, out);
  ASSERT_EQ(out.bytes.size(), 16u);
  for (int x = 0; x < 3; ++x) {
    const Rgb p = image.at(x, 0);
    for (int ch = 0; ch < 3; ++ch) {
      const float v = ch == 0 ? p.r : ch == 1 ? p.g : p.b;
      EXPECT_NEAR(int(out.bytes[std::size_t(x * 4 + ch)]), int(to_byte(linear_to_srgb(std::clamp(v, 0.0f, 1.0f)))), 1);
    }
    EXPECT_EQ(out.bytes[std::size_t(x * 4 + 3)], 255);
  }
  view::to_display(image, view::Display::Beauty, 1, out);  // one stop: twice the radiance
  EXPECT_NEAR(int(out.bytes[1]), int(to_byte(linear_to_srgb(0.5f))), 1);
}

TEST(ViewFileWatch, SeesEveryKindOfChange) {
  test::TempDir dir;
  const fs::path f = dir / "scene.yaml";
  test::write_text(f, "a");
  view::FileWatch w;
  w.watch({f, dir / "mesh.obj"});
  EXPECT_FALSE(w.changed());
  test::write_text(f, "ab");  // size
  EXPECT_TRUE(w.changed());
  EXPECT_FALSE(w.changed());
  test::write_text(dir / "new", "ab");
  fs::rename(dir / "new", f);  // same size and text, another inode (an editor's save)
  EXPECT_TRUE(w.changed());
  test::write_text(dir / "mesh.obj", "");  // appears
  EXPECT_TRUE(w.changed());
  fs::remove(f);  // disappears
  EXPECT_TRUE(w.changed());
}

TEST(ViewFileWatch, ListsTheSceneAndItsMeshes) {
  const fs::path scene = fs::path(STRAHL_SOURCE_DIR) / "scenes" / "mesh.yaml";
  const auto files = view::scene_files(scene);
  ASSERT_EQ(files.size(), 3u);
  EXPECT_EQ(files[0], scene);
  EXPECT_EQ(files[1], scene.parent_path() / "meshes/torus.obj");
  EXPECT_EQ(files[2], scene.parent_path() / "meshes/icosahedron.obj");
  EXPECT_TRUE(view::scene_files("").empty());
  test::TempDir dir;
  test::write_text(dir / "broken.yaml", "objects: [");
  EXPECT_EQ(view::scene_files(dir / "broken.yaml").size(), 1u);
}

// The still frame is render()'s image, bit for bit, whatever came before it; an interactive
// frame is one sample per pixel at 1/scale of the resolution.
TEST(ViewRenderer, StillFrameIsTheRenderersImage) {
  Scene scene = lecture_scene();
  scene.settings.width = 40;
  scene.settings.height = 24;
  scene.settings.sampling.sampler = SamplerKind::Stratified;
  scene.settings.sampling.spp = 9;
  auto rs = std::make_shared<const RenderScene>(compile(scene));
  const Image expected = render(*rs, RenderOptions{});

  CpuBackend cpu(2);
  view::ViewRenderer r(cpu, 2, 8);
  view::FrameRequest q;
  q.scene = rs;
  q.camera = scene.camera;
  q.width = 40;
  q.height = 24;
  q.max_depth = rs->settings.max_depth;
  q.sampling = rs->sampling;
  q.scale = 2;
  view::FrameRequest moved = q;
  view::orbit(moved.camera, 0.3, 0.1);
  r.submit(moved);  // overtaken at once
  const std::uint64_t n = r.submit(q);
  Image image;
  view::FrameStatus s;
  for (int i = 0; i < 2000; ++i) {
    s = r.status();
    if (s.request == n && !s.interactive && s.finished) break;
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
  }
  ASSERT_TRUE(s.finished && !s.interactive && s.request == n);
  ASSERT_TRUE(r.take_image(image, s, true));
  EXPECT_EQ(s.spp, 9);
  EXPECT_EQ(s.target_spp, 9u);
  EXPECT_EQ(image, expected);
  EXPECT_EQ(s.rays.camera, 40u * 24u * 9u);

  view::ViewRenderer idle(cpu, 2, 8);
  Image small;
  const view::FrameStatus f = idle.render_interactive(q, 4, &small);
  EXPECT_TRUE(f.interactive && f.finished);
  EXPECT_EQ(small.width(), 10);
  EXPECT_EQ(small.height(), 6);
  EXPECT_EQ(f.rays.camera, 60u);
  EXPECT_EQ(f.spp, 1);
}

// --device in the viewer (device_backend.h) where no GPU is usable: the CPU renders every frame,
// the same image; `cuda` says why the GPU does not render a new scene; `cpu` never asks.
TEST(ViewDeviceBackend, WithoutAGpuTheCpuRendersTheSameImage) {
  Scene scene = lecture_scene();
  scene.settings.width = 32;
  scene.settings.height = 20;
  auto rs = std::make_shared<const RenderScene>(compile(scene));
  view::DeviceBackend cpu("cpu", 2), cuda("cuda", 2);
  EXPECT_EQ(cpu.use_scene(rs), "");
  EXPECT_EQ(cpu.device_name(), "cpu");
  const std::string why = cuda.use_scene(rs);
  if (cuda.device_name() != "cpu") GTEST_SKIP() << "a GPU is usable here: " << cuda.device_name();
  EXPECT_NE(why.find("the GPU does not render this scene ("), std::string::npos) << why;
  EXPECT_NE(why.find("; rendering on the CPU"), std::string::npos) << why;
  const Image expected = render(*rs, RenderOptions{});
  for (view::DeviceBackend* b : {&cpu, &cuda}) {
    RenderJob job(rs->view(), rs->sampling);
    job.run(*b);
    EXPECT_EQ(job.image(), expected) << b->device_name();
    EXPECT_EQ(b->take_failure(), "");
  }
}

}  // namespace
}  // namespace strahl::view_test
