#include "gpu/DispatchGrid.h"

#include "core/Check.h"
#include "gpu/Context.h"

#include <epoxy/gl.h>

#include <algorithm>

namespace bounce::gl {

namespace {
uint32_t g_maxGroupsXForTests = 0;
}

uint32_t maxGroupsX() {
    const Context* c = Context::current();
    // Without a context (unit tests of callers) GL 4.5's guaranteed minimum.
    constexpr uint32_t kGl45MinGroups = 65535;
    const uint32_t device = c && c->info().maxComputeWorkGroupCount[0] > 0
                                ? static_cast<uint32_t>(c->info().maxComputeWorkGroupCount[0])
                                : kGl45MinGroups;
    return g_maxGroupsXForTests > 0 ? std::min(g_maxGroupsXForTests, device) : device;
}

void setMaxGroupsXForTests(uint32_t limit) { g_maxGroupsXForTests = limit; }

void dispatchGroupsLinear(uint64_t groups) {
    const GroupGrid g = groupGrid(groups, maxGroupsX());
    if (g.x == 0) return;
    const Context* c = Context::current();
    const int maxY = c ? c->info().maxComputeWorkGroupCount[1] : 65535;
    BOUNCE_CHECK(maxY <= 0 || g.y <= static_cast<uint32_t>(maxY), "{} work groups need {} rows, past GL_MAX_COMPUTE_WORK_GROUP_COUNT[1] = {}",
                 groups, g.y, maxY);
    glDispatchCompute(g.x, g.y, 1);
}

void dispatchLinear(uint64_t invocations, uint32_t localSize) {
    dispatchGroupsLinear((invocations + localSize - 1) / localSize);
}

}  // namespace bounce::gl
