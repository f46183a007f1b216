#pragma once
// One headless GL context per process, made on first use and reused: a study job runner, `bounce
// render` and `import bounce` (whose GL work all runs on one thread, python/src/GlThread.h) share it.
// It lives until the process exits, so whatever GL objects outlive their user are deleted while it is
// still current.
#include "core/Error.h"
#include "gpu/Context.h"

#include <string>

namespace bounce {

// Creates the context on the calling thread the first time (EGL, as `bounce render`, on the device
// --gpu / BOUNCE_EGL_DEVICE selects, docs/gpu.md) with `config`; afterwards returns it, whatever
// config a later call asks for. Failure is not remembered: a later call tries again.
Expected<gl::Context*> processContext(const gl::ContextConfig& config = {});
// Destroys the context now (on the thread that made it, after every GL object of the process is gone);
// a later processContext() makes a new one. `import bounce` calls it at interpreter exit.
void releaseProcessContext();

// The global option `--gpu N` (and `bounce.select_gpu(n)`): checks N against the EGL device
// enumeration (one line naming the device count otherwise) and makes it this process's device and its
// child processes' (BOUNCE_EGL_DEVICE). Takes effect for contexts made afterwards; `source` names the
// option in messages.
Expected<void> selectGpu(const std::string& index, const std::string& source);
// Whether the process context exists (a later selectGpu would not move it).
bool processContextExists();

}  // namespace bounce
