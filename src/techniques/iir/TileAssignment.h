#pragma once
// Which interleaved-sampling tile each VPL gathers in (Laine et al. 2007 §5.1: "each VPL is assigned
// to one tile so that each tile has approximately the same number of lights"; §7: "in the order they
// are generated"). GL-free, so that bounce_tests checks it without a context.
//
// A VPL keeps its tile for its whole life: the assignment is remembered per slot together with the
// VPL's serial (VplSample::serial, unique over the distribution's lifetime), and only VPLs without a
// tile (the new ones) are dealt. Re-dealing every frame would move every VPL created after a deleted
// one to another tile, so the n x m interleaving pattern of a surviving VPL would jump from frame to
// frame, which is flicker the incremental method exists to avoid.
//
// Dealing: new VPLs in creation order, each to the least-loaded tile; ties go round robin (the first
// least-loaded tile at or after the one following the last tile dealt). From an empty assignment that
// is plain round robin in generation order, the paper's rule; afterwards it refills the tiles that
// lost VPLs, so the counts stay as even as the survivors allow.
#include "techniques/iir/VplDistribution.h"

#include <cstdint>
#include <span>
#include <vector>

namespace bounce {

class TileAssignment {
public:
    TileAssignment() = default;
    TileAssignment(uint32_t tiles, size_t slots);

    // Brings the assignment up to date with `samples` (indexed by slot, at most `slots` entries):
    // slots that no longer hold the VPL they were dealt for give their tile's place back, then every
    // VPL without a tile is dealt. Returns the slots dealt this call, in the order dealt.
    std::vector<SlotId> update(std::span<const VplSample> samples);

    // Tile of the VPL in `slot`, or -1 when the slot holds no dealt VPL.
    int tileOf(SlotId slot) const;
    uint32_t count(uint32_t tile) const { return m_counts.at(tile); }
    uint32_t tileCount() const { return static_cast<uint32_t>(m_counts.size()); }

private:
    struct Entry {
        int tile = -1;
        uint64_t serial = 0;
    };
    std::vector<Entry> m_slots;
    std::vector<uint32_t> m_counts;
    uint32_t m_cursor = 0;  // the tile after the last one dealt
};

}  // namespace bounce
