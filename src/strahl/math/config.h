#pragma once
// One place for the kernel's floating-point type and the host/device marker.

#include <limits>

#if defined(__CUDACC__)
#define STRAHL_HOST_DEVICE __host__ __device__
#else
#define STRAHL_HOST_DEVICE
#endif

// For the few hot kernel functions the compiler declines to inline on its own (traversals).
#if defined(__CUDACC__)
#define STRAHL_FORCE_INLINE __forceinline__
#elif defined(__GNUC__)
#define STRAHL_FORCE_INLINE inline __attribute__((always_inline))
#else
#define STRAHL_FORCE_INLINE inline
#endif

// For rarely taken branches kept out of hot loops (thin lens, area lights), so their code does
// not crowd the registers of the common path.
#if defined(__CUDACC__)
#define STRAHL_NOINLINE __noinline__
#elif defined(__GNUC__)
#define STRAHL_NOINLINE __attribute__((noinline))
#else
#define STRAHL_NOINLINE
#endif

// For big kernel functions called from many places (the expression interpreter): one copy in
// device code, where ptxas's time grows faster than the functions it is given; the host compiler
// inlines them as it sees fit.
#if defined(__CUDA_ARCH__)
#define STRAHL_DEVICE_NOINLINE __noinline__
#else
#define STRAHL_DEVICE_NOINLINE inline
#endif

namespace strahl {

// Radiance, geometry and ray parameters use this type everywhere; double keeps
// scenes far from the origin (or scaled by 1e-3 .. 1e4) free of self-intersection.
using Real = double;

inline constexpr Real kInfinity = std::numeric_limits<Real>::infinity();
inline constexpr Real kNaN = std::numeric_limits<Real>::quiet_NaN();
inline constexpr Real kPi = Real(3.14159265358979323846);

// Offset of secondary-ray origins from a surface, relative to the magnitudes the hit point was
// computed from (its coordinates and the primitive's: render/surface_point.h), never absolute,
// so that a scene renders the same at any scale.
inline constexpr Real kRayEpsilon = Real(1e-9);
// ... plus this fraction of the path that led to the hit (|origin| + t: the rounding of o + t·d).
inline constexpr Real kRayPathEpsilon = Real(1e-12);

}  // namespace strahl
