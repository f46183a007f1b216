// Default options of the sanitizer runtimes, compiled into every executable of the `sanitize` preset
// (cmake/Sanitize.cmake). The runtimes call these before main; ASAN_OPTIONS, LSAN_OPTIONS and
// UBSAN_OPTIONS in the environment still override them.

#include <dlfcn.h>

#include <initializer_list>

extern "C" {

// detect_stack_use_after_return: off, it doubles the stack of every frame and llvmpipe's worker threads
// already run deep. strict_string_checks: libc string functions must see terminated strings.
const char* __asan_default_options() {
    return "detect_leaks=1:strict_string_checks=1:check_initialization_order=1:detect_stack_use_after_return=0:"
           "abort_on_error=0:exitcode=23";
}

const char* __ubsan_default_options() { return "print_stacktrace=1:halt_on_error=1"; }

// Leaks inside Debian's uninstrumented GL stack are not bounce's: Mesa keeps compiled shaders, the
// screen and LLVM's JIT state until exit, and the GL dispatch libraries keep their tables. A stack that
// passes through one of these libraries is not reported; a leak allocated by bounce's own code (its
// stack starts in bounce) still is, unless it was allocated from inside a GL call.
const char* __lsan_default_suppressions() {
    return "leak:libLLVM\n"
           "leak:libgallium\n"
           "leak:_dri.so\n"
           "leak:libEGL_mesa\n"
           "leak:libglapi\n"
           "leak:libGLdispatch\n"
           "leak:libGLX_mesa\n"
           "leak:libX11\n"
           "leak:libdrm\n"
           // assimp 5.2.5's PLY reader leaks its half-built element list when a body line does not
           // match the header (found by fuzz_model; bounce owns the Assimp::Importer, which frees all
           // it returns). Debian's build has no frame pointers, so its stacks end in the library.
           "leak:libassimp\n";
}

}  // extern "C"

namespace {

// Mesa's DRI driver (llvmpipe's home) is dlclose()d when EGL shuts down, before LeakSanitizer looks:
// its leaks would then show as "<unknown module>", which no suppression can name. Loading it once more
// with RTLD_NODELETE keeps it mapped to the end. Where it is not installed (NVIDIA's EGL), nothing to do.
[[maybe_unused]] const bool kDriverPinned = [] {
    for (const char* path : {"/usr/lib/x86_64-linux-gnu/dri/swrast_dri.so", "/usr/lib/dri/swrast_dri.so"})
        if (dlopen(path, RTLD_LAZY | RTLD_NODELETE | RTLD_LOCAL)) return true;
    return false;
}();

}  // namespace

