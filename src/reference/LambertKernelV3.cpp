// The vectorised kernel for x86-64-v3: AVX2 and FMA (Haswell and later); CMake compiles this file with -march=x86-64-v3.
#define BOUNCE_LAMBERT_ISA v3
#include "reference/LambertKernelIsa.inl"
