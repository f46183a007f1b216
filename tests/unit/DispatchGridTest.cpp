// gl::groupGrid (src/gpu/DispatchGrid.h, issue 29 #5): a 1D job's work groups as rows of at most the
// device's x limit. The grid must cover every group and add less than one row.
#include "gpu/DispatchGrid.h"

#include <gtest/gtest.h>

using bounce::gl::GroupGrid;
using bounce::gl::groupGrid;

TEST(DispatchGrid, FitsInOneRowUpToTheLimitAndWrapsPastIt) {
    constexpr uint32_t kGl45Groups = 65535;  // GL_MAX_COMPUTE_WORK_GROUP_COUNT's GL 4.5 minimum
    EXPECT_EQ(groupGrid(0, kGl45Groups), (GroupGrid{0, 0}));
    EXPECT_EQ(groupGrid(1, kGl45Groups), (GroupGrid{1, 1}));
    EXPECT_EQ(groupGrid(kGl45Groups, kGl45Groups), (GroupGrid{kGl45Groups, 1}));
    EXPECT_EQ(groupGrid(kGl45Groups + 1, kGl45Groups), (GroupGrid{kGl45Groups, 2}));
    // A 4K output's full subsplat list: 3840 x 2160 cells at 64 per group = 129,600 groups.
    EXPECT_EQ(groupGrid(3840ull * 2160 / 64, kGl45Groups), (GroupGrid{kGl45Groups, 2}));
    // Radiosity's mip integration at hemicubeSize=512: 16 hemicubes x 5 faces x 512^2 / 256 = 81,920.
    EXPECT_EQ(groupGrid(16ull * 5 * 512 * 512 / 256, kGl45Groups), (GroupGrid{kGl45Groups, 2}));
}

TEST(DispatchGrid, CoversEveryGroupWithLessThanOneSpareRow) {
    for (uint32_t maxX : {1u, 3u, 64u, 65535u})
        for (uint64_t groups : {1ull, 2ull, 63ull, 64ull, 65ull, 1000ull, 65535ull, 65536ull, 200000ull, 4294836225ull}) {
            const GroupGrid g = groupGrid(groups, maxX);
            ASSERT_LE(g.x, maxX);
            const uint64_t cells = static_cast<uint64_t>(g.x) * g.y;
            EXPECT_GE(cells, groups) << groups << " groups, rows of " << maxX;
            EXPECT_LT(cells - groups, g.x) << groups << " groups, rows of " << maxX;
        }
}
