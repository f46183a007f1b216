#pragma once
// Compute dispatches of more work groups than one dimension allows (issue 29 #5). GL 4.5 guarantees
// GL_MAX_COMPUTE_WORK_GROUP_COUNT = 65,535 per dimension (llvmpipe and AMD/Intel report exactly that
// for x too); a 1D job of n items at 64 per group passes it at n = 4.19M (a 4K output's subsplat list;
// radiosity's 16 hemicubes at hemicubeSize=512 resolved 256 texels a group: 81,920 groups), and a
// dispatch past it is GL_INVALID_VALUE (direct) or undefined (indirect). The groups are laid out row
// by row instead, rows of at most the x limit; the shader numbers them with linearInvocation() or
// linearGroup() (shaders/common/dispatch.glsl) and bounds-checks the index against its count, which
// drops the last row's extra groups.
#include <cstdint>

namespace bounce::gl {

struct GroupGrid {
    uint32_t x = 0, y = 0;
    bool operator==(const GroupGrid&) const = default;
};

// `groups` work groups in rows of at most `maxX`: x = min(groups, maxX), y = ceil(groups / maxX);
// 0 groups give 0 x 0.
constexpr GroupGrid groupGrid(uint64_t groups, uint32_t maxX) {
    if (groups == 0 || maxX == 0) return {};
    return {static_cast<uint32_t>(groups < maxX ? groups : maxX), static_cast<uint32_t>((groups + maxX - 1) / maxX)};
}

// The current context's GL_MAX_COMPUTE_WORK_GROUP_COUNT[0], or a test's lower value.
uint32_t maxGroupsX();
// A test lowers the x limit (0: the device's own) so that grids wrap at llvmpipe-sized jobs.
void setMaxGroupsXForTests(uint32_t limit);

// Dispatches `groups` groups of the bound compute program as groupGrid(groups, maxGroupsX()).
// BOUNCE_CHECKs the rows against GL_MAX_COMPUTE_WORK_GROUP_COUNT[1] (65,535^2 groups: unreachable).
void dispatchGroupsLinear(uint64_t groups);
// The same for `invocations` items at `localSize` invocations per group (the program's local_size_x).
void dispatchLinear(uint64_t invocations, uint32_t localSize);

}  // namespace bounce::gl
