// strahl-diff A B [DIFF]: compares two images (PNG 8/16-bit, JPEG, PPM, PFM, EXR) on values
// clamped to 0..1 as 8/16-bit files store them: RMSE, PSNR, largest difference, pixels that
// differ (compare.h); optionally writes |A − B| × 10 as an image. Exit codes (docs/cli.md):
// 0 compared, 1 usage, 2 an image cannot be read or written, the sizes differ, DIFF is one of
// the inputs or the report cannot be written, 3 compared but an image holds NaN or infinite values.

#include <sys/stat.h>

#include <string>

#include "compare.h"
#include "console.h"
#include "strahl/image/image_io.h"
#include "strahl/util/error.h"

namespace {

// The same file under any name (hard links, symbolic links, ./a.png and a.png): same device and inode.
bool same_file(const char* x, const char* y) {
  struct stat sx {}, sy {};
  return ::stat(x, &sx) == 0 && ::stat(y, &sy) == 0 && sx.st_dev == sy.st_dev && sx.st_ino == sy.st_ino;
}

// The difference image must not replace either input, and must be writable, before any work.
void check_difference_path(char** argv) {
  for (int input = 1; input <= 2; ++input)
    if (same_file(argv[3], argv[input]))
      throw strahl::Error(std::string(argv[3]) + ": the difference image would overwrite the input image '" +
                          argv[input] + "'; give it another name");
  strahl::check_output_path(argv[3]);
}

int run(int argc, char** argv) {
  using namespace strahl;
  if (argc == 4) check_difference_path(argv);
  const diff::Comparison c = diff::compare(read_image(argv[1]), read_image(argv[2]));
  console::out("rmse {:.3e}  psnr {:.2f} dB  max {:.4f}  pixels differing by more than 1/255: {} of {}\n", c.rmse,
               c.psnr, c.max, c.differing, c.difference.pixels().size());
  for (int k = 0; k < 2; ++k)
    if (c.non_finite[k] > 0)
      console::err("strahl-diff: warning: {}: {} values are NaN or infinite; they count as different\n", argv[1 + k],
                   c.non_finite[k]);
  if (argc == 4) write_image(c.difference, argv[3], {true});
  if (console::lost(console::Stream::out)) {
    console::err("strahl-diff: error: the result could not be written to stdout\n");
    return 2;
  }
  return c.non_finite[0] + c.non_finite[1] > 0 ? 3 : 0;
}

}  // namespace

int main(int argc, char** argv) {
  strahl::console::protect_streams();
  if (argc != 3 && argc != 4) {
    strahl::console::err("usage: strahl-diff IMAGE_A IMAGE_B [DIFF_IMAGE]\n");
    return 1;
  }
  if (argc == 4 && !strahl::is_supported_image_extension(argv[3])) {
    strahl::console::err("strahl-diff: error: {}: unknown image format\n", argv[3]);
    return 1;
  }
  try {
    return run(argc, argv);
  } catch (const std::exception& err) {
    strahl::console::err("strahl-diff: error: {}\n", err.what());
    return 2;
  }
}
