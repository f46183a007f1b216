#pragma once
// One headless GL context per process, made on first use and reused: a study job runner, `bounce
// render` and `import bounce` (whose GL work all runs on one thread, python/src/GlThread.h) share it.
// It lives until the process exits, so whatever GL objects outlive their user are deleted while it is
// still current.
#include "core/Error.h"
#include "gpu/Context.h"

namespace bounce {

// Creates the context on the calling thread the first time (EGL, as `bounce render`); afterwards
// returns it. Failure is not remembered: a later call tries again.
Expected<gl::Context*> processContext();
// Destroys the context now (on the thread that made it, after every GL object of the process is gone);
// a later processContext() makes a new one. `import bounce` calls it at interpreter exit.
void releaseProcessContext();

}  // namespace bounce
