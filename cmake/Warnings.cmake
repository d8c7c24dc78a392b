# Warnings for every strahl target; -Werror in CI (STRAHL_WERROR=ON). These and the options
# below are C++ compiler flags: the CUDA translation units (src/strahl/cuda) get their own.
add_library(strahl_warnings INTERFACE)
target_compile_options(strahl_warnings INTERFACE $<$<COMPILE_LANGUAGE:CXX>:-Wall -Wextra -Wpedantic -Wshadow -Wnon-virtual-dtor>)
if(STRAHL_WERROR)
  target_compile_options(strahl_warnings INTERFACE $<$<COMPILE_LANGUAGE:CXX>:-Werror>)
endif()

add_library(strahl_optimise INTERFACE)
# Nothing reads errno after maths calls; without it sqrt() needs no libm call for negative
# arguments and loops over shapes vectorise.
target_compile_options(strahl_optimise INTERFACE $<$<COMPILE_LANGUAGE:CXX>:-fno-math-errno>)
# No fused multiply-add contraction: the watertight triangle test (geometry/triangle.h) relies on
# a·b − c·d being computed the same way, with both products rounded, for the two triangles that
# share an edge. GCC contracts across statements by default in C++ where the CPU has FMA.
target_compile_options(strahl_optimise INTERFACE $<$<COMPILE_LANGUAGE:CXX>:-ffp-contract=off>)
# Floating-point operations never trap here (strahl enables no FP exceptions), so GCC may compute
# both sides of a select: the loops over a packet's lanes (accel/packet.h, render/packet_radiance.h)
# vectorise only so. No value changes: this flag licenses no reassociation or contraction.
target_compile_options(strahl_optimise INTERFACE $<$<COMPILE_LANGUAGE:CXX>:-fno-trapping-math>)
if(STRAHL_NATIVE)
  target_compile_options(strahl_optimise INTERFACE $<$<COMPILE_LANGUAGE:CXX>:-march=native>)
endif()
# GCC 12 reports false -Wrestrict positives inside std::string concatenation (GCC bug 105651).
if(CMAKE_CXX_COMPILER_ID STREQUAL "GNU" AND CMAKE_CXX_COMPILER_VERSION VERSION_LESS 13)
  target_compile_options(strahl_warnings INTERFACE $<$<COMPILE_LANGUAGE:CXX>:-Wno-restrict>)
endif()
