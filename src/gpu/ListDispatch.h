#pragma once
// Compute jobs over a list a shader built (an atomic append), dispatched indirectly so that the
// list's length never comes back to the CPU: a one-invocation pass (shaders/common/list_args.comp)
// turns the count in the list's first word into a DispatchIndirectCommand of 64-wide groups in rows
// of at most maxGroupsX() (DispatchGrid.h, issue 29 #5); the job numbers its invocations with
// dispatch.glsl's linearInvocation() and bounds-checks against min(count, capacity).
// One home for the stencilled gather's cell list (isr, hisr) and vct's active-voxel lists, whose
// passes were point lists drawn with the rasterizer off: GL leaves the number of vertex-shader
// invocations that load and store undefined (the specification's "Shader Memory Access Ordering"),
// and those passes write (issue 29 #17).
#include "core/Error.h"
#include "gpu/Objects.h"
#include "gpu/Program.h"

#include <cstdint>
#include <limits>

namespace bounce::gl {

class ListDispatch {
public:
    static constexpr uint32_t kUnbounded = std::numeric_limits<uint32_t>::max();

    static Expected<ListDispatch> create();
    // Writes `args` (3 uint32) from the count in the first word of `list`, clamped to `capacity`
    // entries, in rows of maxX groups (0: maxGroupsX()). Orders the count's shader writes before it,
    // and the arguments before the indirect dispatch and any shader read after it (storage and
    // command barriers). Binds TECH2 and TECH3.
    void writeArgs(const Buffer& list, const Buffer& args, uint32_t capacity = kUnbounded, uint32_t maxX = 0);
    // Dispatches the bound program with the arguments writeArgs left in `args`.
    static void dispatch(const Buffer& args);
    // 12 bytes: a DispatchIndirectCommand.
    static Buffer createArgs(std::string_view label);

private:
    Program m_args;
};

}  // namespace bounce::gl
