#pragma once
// Regular-grid VPL extraction from a reflective shadow map (Nichols 2010 §3.2.1, checklist item 3):
// grid^2 VPLs per RSM layer, each carrying the summed flux of its block, written to the VPL cache
// (an SSBO of Vpl records, shaders/techniques/nichols/vpl.glsl) that every gather reads.
#include "techniques/nichols/ReflectiveShadowMap.h"

namespace bounce::nichols {

// std430 layout of shaders/techniques/nichols/vpl.glsl's Vpl.
struct VplRecord {
    glm::vec4 position;  // xyz, w valid
    glm::vec4 normal;    // xyz, w area m^2
    glm::vec4 flux;      // rgb W, w texels represented
};
static_assert(sizeof(VplRecord) == 48);

class RegularVpls {
public:
    static Expected<RegularVpls> create();
    // The settings check of every technique with a regular VPL grid: grid divides rsmSize, and one
    // VPL's block of (rsmSize / grid)^2 texels fits the extraction's shader loop budget
    // (gpu/ShaderLimits.h; blocks up to 128^2), and the cache of grid^2 x layers VPLs (the RSM's layers:
    // ReflectiveShadowMap::layersFor) fits a storage buffer of this GL (issue 29 #6: vplGrid=2048 with a
    // cube RSM is 1.2 GB).
    static Expected<void> checkGrid(int rsmSize, int grid, int layers);
    // grid must divide rsm.size(); both are powers of two in practice (BOUNCE_CHECKed).
    void extract(const ReflectiveShadowMap& rsm, int grid);

    int count() const { return m_count; }
    int grid() const { return m_grid; }
    int layers() const { return m_layers; }
    const gl::Buffer& buffer() const { return m_buffer; }
    // The same records as grid x grid x layers RGBA32F 2D arrays (position, normal, flux; texel
    // (x, y, layer) = record (layer * grid + y) * grid + x): a gather that walks them with texelFetch in
    // nested loops runs about twice as fast on llvmpipe as one indexing the SSBO (measured, see rsm.md).
    const gl::Texture& positionTexture() const { return m_position; }
    const gl::Texture& normalTexture() const { return m_normal; }
    const gl::Texture& fluxTexture() const { return m_flux; }
    std::vector<VplRecord> download() const;
    // The viewer's "vpl.points": the VPLs' positions as points over the image.
    void debugViews(std::vector<DebugView>& out) const {
        if (m_position) out.push_back({"vpl.points", &m_position, DebugEncoding::Points, 7.0f});
    }

private:
    gl::Program m_program;
    gl::Buffer m_buffer;
    gl::Texture m_position, m_normal, m_flux;
    int m_count = 0, m_grid = 0, m_layers = 0;
};

}  // namespace bounce::nichols
