// Chooses the vectorised kernel's variant once, from what the CPU supports.
#include "reference/LambertKernel.h"

namespace bounce::lambert {

namespace {

struct Variant {
    const char* name;
    void (*hit)(Lanes&, int, bool) noexcept;
    void (*reflect)(Lanes&, int) noexcept;
};

Variant choose() noexcept {
// GCC only: CMake builds the v3/v4 files for their instruction sets with GCC alone, and clang 14
// (the fuzz build) knows no "x86-64-v4" feature string.
#if defined(__x86_64__) && defined(__GNUC__) && !defined(__clang__)
    __builtin_cpu_init();
    if (__builtin_cpu_supports("x86-64-v4")) return {"x86-64-v4", v4::hit, v4::reflect};
    if (__builtin_cpu_supports("x86-64-v3")) return {"x86-64-v3", v3::hit, v3::reflect};
#endif
    return {"x86-64", base::hit, base::reflect};
}

const Variant& variant() noexcept {
    static const Variant chosen = choose();
    return chosen;
}

}  // namespace

const char* instructionSet() noexcept { return variant().name; }

void hit(Lanes& lanes, int maxReflections, bool indirectOnly) noexcept {
    variant().hit(lanes, maxReflections, indirectOnly);
}

void reflect(Lanes& lanes, int rouletteStartReflections) noexcept { variant().reflect(lanes, rouletteStartReflections); }

}  // namespace bounce::lambert
