#pragma once
// Synchronous GPU->CPU reads on a frame's path (issue 18). A read that waits for the GPU (a query's
// result, a buffer or texture download, glReadPixels, glFinish, a fence wait) in the middle of a frame
// stops the CPU from queueing the rest of the frame until the GPU has caught up: on a GPU that is an
// idle bubble, on llvmpipe a flush of the deferred rasteriser at a point of the frame's choosing.
// Pipeline::renderFrame marks the span in which a frame's work is submitted with a FramePath; a
// technique reads its counters after that span (Technique::collectCounters), when the frame's work
// is queued whole.
//
// installReadbackHooks() wraps libepoxy's GL entry points of the blocking reads (epoxy's dispatch is a
// table of writable function pointers) so that every call made inside a FramePath is logged with its
// name; tests/gpu/ReadbackGpuTest.cpp installs it and renders every registered technique. Reads that
// do not wait are not logged: GL_QUERY_RESULT_AVAILABLE and GL_QUERY_RESULT_NO_WAIT, and query results
// written into a bound GL_QUERY_BUFFER. The same hooks tell the barrier tracker (gpu/BarrierTracker.h)
// of CPU reads of buffers and textures.
#include <string>
#include <vector>

namespace bounce::gl {

// Marks the span of a frame's submission (nests).
class FramePath {
public:
    FramePath();
    ~FramePath();
    FramePath(const FramePath&) = delete;
    FramePath& operator=(const FramePath&) = delete;
};

bool inFramePath();

// Wraps the blocking-read entry points (idempotent). Needs a current EGL context: the real entry points
// are resolved through eglGetProcAddress.
void installReadbackHooks();
bool readbackHooksInstalled();

// Names of the blocking reads made inside a FramePath since the last reset, in call order.
const std::vector<std::string>& framePathReadbacks();
void resetFramePathReadbacks();

}  // namespace bounce::gl
