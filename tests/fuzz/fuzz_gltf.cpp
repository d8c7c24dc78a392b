// libFuzzer target: the glTF loader and compile() (see fuzz_entries.h, docs/testing.md).
#include "fuzz_entries.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  (void)strahl::fuzz::gltf_input(data, size);
  return 0;
}
