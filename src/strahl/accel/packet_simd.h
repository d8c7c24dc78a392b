#pragma once
// How the packet traversal (wide_bvh_packet.h, packet_boxes.h, packet_leaves.h) is built: with
// AVX-512 (16 lanes at once), AVX2 (8) or the portable scalar path, and without two GCC warnings.

// STRAHL_PORTABLE_KERNELS: the scalar path on a SIMD host too (the tests compare them).
#if !defined(__CUDACC__) && defined(__AVX2__) && !defined(STRAHL_PORTABLE_KERNELS)
#include <immintrin.h>
#define STRAHL_PACKET_AVX2 1
#if defined(__AVX512F__)
#define STRAHL_PACKET_AVX512 1
#endif
#endif

// GCC 12 warns about the undefined vectors inside its own AVX-512 intrinsics (GCC bug 105593)
// wherever they are inlined; STRAHL_PACKET_WARNINGS_OFF / _ON turn the warning off for the bodies
// of the packet headers only.
#if defined(__GNUC__) && !defined(__clang__)
#define STRAHL_PACKET_WARNINGS_OFF                                   \
  _Pragma("GCC diagnostic push")                                     \
  _Pragma("GCC diagnostic ignored \"-Wmaybe-uninitialized\"")       \
  _Pragma("GCC diagnostic ignored \"-Wuninitialized\"")
#define STRAHL_PACKET_WARNINGS_ON _Pragma("GCC diagnostic pop")
#else
#define STRAHL_PACKET_WARNINGS_OFF
#define STRAHL_PACKET_WARNINGS_ON
#endif
