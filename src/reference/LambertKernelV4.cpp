// The vectorised kernel for x86-64-v4: AVX-512 (Skylake-SP and later); CMake compiles this file with -march=x86-64-v4.
#define BOUNCE_LAMBERT_ISA v4
#include "reference/LambertKernelIsa.inl"
