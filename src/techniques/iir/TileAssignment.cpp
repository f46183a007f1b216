#include "techniques/iir/TileAssignment.h"

#include "core/Check.h"

#include <algorithm>

namespace bounce {

TileAssignment::TileAssignment(uint32_t tiles, size_t slots) : m_slots(slots), m_counts(tiles, 0) {
    BOUNCE_CHECK(tiles > 0, "TileAssignment needs at least one tile");
}

std::vector<SlotId> TileAssignment::update(std::span<const VplSample> samples) {
    BOUNCE_CHECK(samples.size() <= m_slots.size(), "TileAssignment: {} samples for {} slots", samples.size(),
                 m_slots.size());
    // Free the tiles of VPLs that are gone (slot empty, a miss, or reused by a newer sample).
    for (size_t slot = 0; slot < m_slots.size(); ++slot) {
        Entry& e = m_slots[slot];
        if (e.tile < 0) continue;
        const bool same = slot < samples.size() && samples[slot].kind == SampleKind::Vpl &&
                          samples[slot].serial == e.serial;
        if (!same) {
            --m_counts[static_cast<size_t>(e.tile)];
            e.tile = -1;
        }
    }
    std::vector<SlotId> fresh;
    for (size_t slot = 0; slot < samples.size(); ++slot)
        if (samples[slot].kind == SampleKind::Vpl && m_slots[slot].tile < 0) fresh.push_back(static_cast<SlotId>(slot));
    std::sort(fresh.begin(), fresh.end(), [&](SlotId a, SlotId b) { return samples[a].serial < samples[b].serial; });
    // An empty assignment starts the round robin at tile 0 (the comparison mode re-deals everything
    // every frame and so gets the same pattern every frame).
    if (std::all_of(m_counts.begin(), m_counts.end(), [](uint32_t c) { return c == 0; })) m_cursor = 0;
    const uint32_t tiles = tileCount();
    for (SlotId slot : fresh) {
        const uint32_t least = *std::min_element(m_counts.begin(), m_counts.end());
        uint32_t tile = m_cursor;
        while (m_counts[tile] != least) tile = (tile + 1) % tiles;
        ++m_counts[tile];
        m_slots[slot] = {static_cast<int>(tile), samples[slot].serial};
        m_cursor = (tile + 1) % tiles;
    }
    return fresh;
}

int TileAssignment::tileOf(SlotId slot) const { return slot < m_slots.size() ? m_slots[slot].tile : -1; }

}  // namespace bounce
