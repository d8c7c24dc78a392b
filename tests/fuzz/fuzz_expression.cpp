// libFuzzer target: the implicit-surface expression compiler and evaluator (see fuzz_entries.h,
// docs/testing.md).
#include "fuzz_entries.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  (void)strahl::fuzz::expression_input(data, size);
  return 0;
}
