// The vectorised kernel for the x86-64 baseline (SSE2): runs on every x86-64 CPU.
#define BOUNCE_LAMBERT_ISA base
#include "reference/LambertKernelIsa.inl"
