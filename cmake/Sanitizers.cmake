# Sanitizers for every target (STRAHL_SANITIZE=address,undefined in the asan-ubsan preset):
# any finding aborts the test that caused it (-fno-sanitize-recover), so ctest reports it.
if(STRAHL_SANITIZE)
  add_compile_options(-fsanitize=${STRAHL_SANITIZE} -fno-sanitize-recover=all -fno-omit-frame-pointer)
  add_link_options(-fsanitize=${STRAHL_SANITIZE})
  # Programs not position-independent: a PIE test program carries 1.7 million dynamic
  # relocations (the sanitizers' metadata), which the loader applies at every start (~0.2 s of the
  # ~0.45 s that each of the suite's ~530 processes takes to start under ASan).
  add_link_options($<$<STREQUAL:$<TARGET_PROPERTY:TYPE>,EXECUTABLE>:-no-pie>)
endif()

# libFuzzer (preset fuzz): the library is instrumented for coverage and checked by ASan and
# UBSan; only the fuzz targets themselves link libFuzzer's main (tests/fuzz/CMakeLists.txt).
if(STRAHL_FUZZ)
  if(NOT CMAKE_CXX_COMPILER_ID MATCHES "Clang")
    message(FATAL_ERROR "STRAHL_FUZZ needs clang (cmake --preset fuzz)")
  endif()
  add_compile_options(-fsanitize=fuzzer-no-link,address,undefined -fno-sanitize-recover=all -fno-omit-frame-pointer)
  add_link_options(-fsanitize=address,undefined)
endif()
