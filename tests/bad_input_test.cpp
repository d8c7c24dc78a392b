// The bad-input corpus (tests/bad-input/, listed with the expected outcome in its EXPECTED file):
// every file goes through the built CLI, which must end within a second of CPU time with the
// expected exit code (2 for a bad scene, mesh or output path, 1 for a usage error), one clear
// message naming file:line:column where there is one, nothing on stdout, and an existing output
// image left exactly as it was (same bytes, same modification time, no stray files beside it).
// Inputs that cannot live in git (FIFOs, devices, unreadable files) are made here.

#include <gtest/gtest.h>
#include <sys/stat.h>

#include <algorithm>
#include <set>
#include <sstream>

#include "child_process.h"
#include "test_helpers.h"

namespace strahl::bad_input_test {
namespace {

const fs::path kCorpus = fs::path(STRAHL_SOURCE_DIR) / "tests" / "bad-input";

struct Case {
  std::string file;
  int exit_code = 2;
  std::string fragment;
  std::vector<std::string> args;
  int line = 0;  // in EXPECTED
};

std::string trim(std::string s) {
  const auto not_space = [](unsigned char c) { return !std::isspace(c); };
  s.erase(s.begin(), std::find_if(s.begin(), s.end(), not_space));
  s.erase(std::find_if(s.rbegin(), s.rend(), not_space).base(), s.end());
  return s;
}

std::string replace_all(std::string s, const std::string& from, const std::string& to) {
  for (std::size_t p = s.find(from); p != std::string::npos; p = s.find(from, p + to.size())) s.replace(p, from.size(), to);
  return s;
}

std::vector<Case> read_manifest(const std::string& tmp) {
  std::istringstream in(test::read_text(kCorpus / "EXPECTED"));
  std::vector<Case> cases;
  std::string line;
  int number = 0;
  while (std::getline(in, line)) {
    ++number;
    if (trim(line).empty() || trim(line)[0] == '#') continue;
    std::vector<std::string> fields;
    std::istringstream split(line);
    for (std::string f; std::getline(split, f, '|');) fields.push_back(f);
    if (fields.size() == 3) fields.emplace_back();  // getline drops an empty last field
    if (fields.size() != 4) {
      ADD_FAILURE() << "EXPECTED:" << number << ": want 'file | exit code | fragment | arguments'";
      continue;
    }
    Case c;
    c.file = trim(fields[0]);
    c.exit_code = std::stoi(fields[1]);
    c.fragment = replace_all(trim(fields[2]), "{tmp}", tmp);
    std::istringstream args(replace_all(trim(fields[3]), "{tmp}", tmp));
    for (std::string a; args >> a;) c.args.push_back(a);
    c.line = number;
    cases.push_back(c);
  }
  return cases;
}

std::set<std::string> listing(const fs::path& dir) {
  std::set<std::string> names;
  for (const auto& e : fs::directory_iterator(dir)) names.insert(e.path().filename().string());
  return names;
}

// A scratch directory holding an output image that no failing run may touch.
class BadInput : public ::testing::Test {
 protected:
  void SetUp() override {
    test::write_text(existing_, "an existing image: any run that fails must leave these bytes alone\n");
    fs::last_write_time(existing_, fs::file_time_type(std::chrono::hours(24 * 365 * 20)));
    fs::create_directory(dir_ / "folder.png");
    fs::create_directory(dir_ / "existing.depth.exr");  // in the way of --aov depth
    mtime_ = fs::last_write_time(existing_);
    before_ = listing(dir_.path());
  }

  // Runs the CLI on `file` (relative to `cwd`) and checks everything a failing run must do.
  void expect_refused(const std::string& where, const fs::path& cwd, const std::string& file, int exit_code,
                      const std::string& fragment, std::vector<std::string> args = {}) {
    std::vector<std::string> argv = {STRAHL_CLI, file, "-q"};
    if (std::find(args.begin(), args.end(), "-o") == args.end()) args.insert(args.end(), {"-o", existing_.string()});
    argv.insert(argv.end(), args.begin(), args.end());
    const test::ChildResult r = test::run_child(argv, cwd, 20);
    SCOPED_TRACE(where + ": strahl " + file);
    ASSERT_FALSE(r.timed_out) << "hung (killed after 20 s)";
    EXPECT_EQ(r.term_signal, 0) << "crashed with signal " << r.term_signal << "\n" << r.err;
    EXPECT_EQ(r.exit_code, exit_code) << r.err;
    EXPECT_LT(r.cpu_seconds, 1.0) << "took " << r.cpu_seconds << " s of CPU time";
    EXPECT_EQ(r.out, "");
    EXPECT_NE(r.err.find(fragment), std::string::npos) << "message: " << r.err << "expected to contain: " << fragment;
    const long lines = std::count(r.err.begin(), r.err.end(), '\n');
    if (exit_code == 2) {
      EXPECT_EQ(lines, 1) << "one message, one line: " << r.err;
      EXPECT_EQ(r.err.rfind("strahl: error: ", 0), 0u) << r.err;
    } else {
      EXPECT_LE(lines, 2) << r.err;  // CLI11's message and its "Run with --help" hint
    }
    EXPECT_EQ(test::read_text(existing_), "an existing image: any run that fails must leave these bytes alone\n");
    EXPECT_TRUE(fs::last_write_time(existing_) == mtime_) << "the existing image was touched";
    EXPECT_EQ(listing(dir_.path()), before_) << "files were left beside the output";
  }

  test::TempDir dir_;
  fs::path existing_ = dir_ / "existing.png";
  fs::file_time_type mtime_;
  std::set<std::string> before_;
};

TEST_F(BadInput, EveryCorpusFileIsRefusedCleanly) {
  const std::vector<Case> cases = read_manifest(dir_.path().string());
  for (const Case& c : cases)
    expect_refused("EXPECTED:" + std::to_string(c.line), kCorpus, c.file, c.exit_code, c.fragment, c.args);
}

TEST_F(BadInput, ManifestCoversTheCorpus) {
  const std::vector<Case> cases = read_manifest(dir_.path().string());
  std::set<std::string> listed;
  for (const Case& c : cases) listed.insert(c.file);
  int scenes = 0, meshes = 0;
  for (const auto& e : fs::directory_iterator(kCorpus)) {
    const std::string name = e.path().filename().string();
    if (name == "EXPECTED" || name == "meshes") continue;
    ++scenes;
    EXPECT_TRUE(listed.count(name)) << name << " is in tests/bad-input/ but not in EXPECTED";
  }
  for (const auto& e : fs::directory_iterator(kCorpus / "meshes")) {
    if (!e.is_regular_file()) continue;
    ++meshes;
    const std::string stem = e.path().stem().string();
    EXPECT_TRUE(listed.count("mesh-" + stem + ".yaml")) << "meshes/" << e.path().filename().string()
                                                        << " has no scene mesh-" << stem << ".yaml";
  }
  EXPECT_GE(scenes, 84);
  EXPECT_GE(meshes, 23);
}

// A FIFO would block a reader forever and /dev/zero never ends: neither may be read.
TEST_F(BadInput, NonRegularFilesAreRefused) {
  test::TempDir d;
  ASSERT_EQ(::mkfifo((d / "fifo.yaml").c_str(), 0600), 0);
  fs::create_symlink("/dev/zero", d / "zero.yaml");
  expect_refused("fifo scene", d.path(), "fifo.yaml", 2, "fifo.yaml: is not a regular file");
  expect_refused("/dev/zero scene", d.path(), "zero.yaml", 2, "zero.yaml: is not a regular file");

  for (const char* ext : {"obj", "ply", "gltf", "glb"}) {
    const std::string fifo = std::string("fifo.") + ext, zero = std::string("zero.") + ext;
    ASSERT_EQ(::mkfifo((d / fifo).c_str(), 0600), 0);
    fs::create_symlink("/dev/zero", d / zero);
    for (const std::string& mesh : {fifo, zero}) {
      test::write_text(d / "scene.yaml", "camera: {position: [0, 1, 3], look_at: [0, 0, 0]}\nobjects:\n"
                                         "  - {type: mesh, file: " + mesh + "}\n");
      expect_refused(mesh, d.path(), "scene.yaml", 2, "scene.yaml:3:24: mesh: " + mesh + ": ");
    }
  }
  // The output itself: a FIFO (or a device) where the image should go would be replaced by the rename.
  ASSERT_EQ(::mkfifo((d / "out.png").c_str(), 0600), 0);
  test::write_text(d / "ok.yaml", "camera: {position: [0, 1, 3], look_at: [0, 0, 0]}\nobjects:\n"
                                  "  - {type: sphere, center: [0, 0, 0], radius: 1}\n");
  expect_refused("fifo output", d.path(), "ok.yaml", 2, "out.png: cannot write the image: it exists and is not a regular file",
                 {"-o", (d / "out.png").string()});
  EXPECT_TRUE(fs::is_fifo(d / "out.png"));
  // ... and one where an AOV should go, checked before the scene is loaded.
  ASSERT_EQ(::mkfifo((d / "aov.normal.exr").c_str(), 0600), 0);
  expect_refused("fifo AOV", d.path(), "ok.yaml", 2, "aov.normal.exr: cannot write the image: it exists and is not a regular file",
                 {"-o", (d / "aov.png").string(), "--aov", "depth,normal"});
  EXPECT_TRUE(fs::is_fifo(d / "aov.normal.exr"));
}

TEST_F(BadInput, UnreadableMeshIsRefused) {
  if (::geteuid() == 0) GTEST_SKIP() << "root reads files without read permission";
  test::TempDir d;
  fs::copy_file(fs::path(STRAHL_SOURCE_DIR) / "scenes" / "meshes" / "icosahedron.obj", d / "locked.obj");
  fs::permissions(d / "locked.obj", fs::perms::none);
  test::write_text(d / "scene.yaml", "camera: {position: [0, 1, 3], look_at: [0, 0, 0]}\nobjects:\n"
                                     "  - {type: mesh, file: locked.obj}\n");
  expect_refused("unreadable mesh", d.path(), "scene.yaml", 2, "locked.obj: cannot open mesh file");
}

TEST_F(BadInput, UnwritableOutputDirectoryIsRefusedBeforeRendering) {
  if (::geteuid() == 0) GTEST_SKIP() << "root writes into directories without write permission";
  test::TempDir d;
  fs::create_directory(d / "locked");
  fs::permissions(d / "locked", fs::perms::owner_read | fs::perms::owner_exec);
  expect_refused("unwritable directory", kCorpus, "good.yaml", 2, "cannot write in directory",
                 {"-o", (d / "locked" / "out.png").string()});
  fs::permissions(d / "locked", fs::perms::owner_all);
}

}  // namespace
}  // namespace strahl::bad_input_test
