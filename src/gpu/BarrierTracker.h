#pragma once
// Missing-glMemoryBarrier checking for tests (issue 29; docs/gpu.md "Memory barriers"). llvmpipe runs
// every shader to completion in submission order, so a missing barrier bit never shows there; on
// NVIDIA/AMD/Intel it gives stale data (radeonsi, for one, invalidates its constant cache only on
// GL_UNIFORM_BARRIER_BIT). The tracker makes it show on llvmpipe.
//
// It wraps libepoxy's entry points of draws and dispatches, glMemoryBarrier, texture binds and object
// deletion (and is told of readbacks by gpu/Readbacks' hooks). At each draw or dispatch it records
// which buffers and textures the current program may write (every storage buffer bound to one of its
// active storage blocks, every texture bound to one of its image units with write access) as having
// every barrier bit pending; glMemoryBarrier(bits) clears those bits on everything written before it.
// A later read is a violation when its bit is still pending:
//   a uniform block              GL_UNIFORM_BARRIER_BIT
//   a sampler / texelFetch (also a buffer texture's buffer)  GL_TEXTURE_FETCH_BARRIER_BIT
//   indirect draw/dispatch args  GL_COMMAND_BARRIER_BIT
//   vertex / index buffers       GL_VERTEX_ATTRIB_ARRAY_BARRIER_BIT / GL_ELEMENT_ARRAY_BARRIER_BIT
//   a buffer readback or map     GL_BUFFER_UPDATE_BARRIER_BIT
//   a texture readback           GL_TEXTURE_UPDATE_BARRIER_BIT
// Storage-buffer and image reads by the next shader are not checked (bounce's passes order those with
// GL_SHADER_STORAGE/IMAGE_ACCESS bits; counting every bound storage block as written would flag
// read-only uses). Writes by other means (uploads, clears, rendering to a framebuffer, transform
// feedback) need no glMemoryBarrier for these reads and are not tracked.
//
// Cheap and off by default: tests turn it on with BOUNCE_BARRIER_CHECK=1 (tests/gpu/GpuTestSupport.h
// then fails a test that reported a violation; the CTest gpu_barrier_check runs the every-technique
// test so). Needs a current EGL context (entry points through eglGetProcAddress).
#include <string>
#include <vector>

namespace bounce::gl {

// Installs the hooks (idempotent, permanent) and turns tracking on or off. Off, the hooks only forward.
void installBarrierTracker();
void setBarrierTracking(bool on);
bool barrierTracking();
// True when BOUNCE_BARRIER_CHECK=1.
bool barrierCheckRequested();

// One line per distinct violation (reader, object, kind) since the last reset, in order.
const std::vector<std::string>& barrierViolations();
void resetBarrierViolations();
// Forgets every pending write (a test's start).
void resetBarrierState();

namespace detail {
// Called by gpu/Readbacks' hooks: a CPU read of a buffer or texture object (0: the one bound to target).
void barrierBufferRead(unsigned buffer, const char* how);
void barrierTextureRead(unsigned texture, const char* how);
// Called by Program::build's audit with the stages' source texts: storage blocks declared `readonly`
// are not counted as written by the program (without a note every active storage block is).
void barrierNoteProgramSources(unsigned program, const std::vector<std::string>& texts);
}  // namespace detail

}  // namespace bounce::gl
