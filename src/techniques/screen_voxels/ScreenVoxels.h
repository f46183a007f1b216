#pragma once
// Screen-space binary voxelization of the camera frustum (Nichols 2010 §5.3.3, checklist item 18;
// Eisemann & Décoret 2006): a columns.x x columns.y grid of `bits`-bit columns, one bit per linear
// depth slice, built in one pass over all geometry with logical-OR blending into RGBA32UI targets
// (128 bits each, up to SV_MAX_LAYERS), and marched by shaders/techniques/screen_voxels/march.glsl.
// Shared machinery: the area-light technique's visibility (ch. 5) and the optional VPL visibility of
// the RSM-family gathers use it.
#include "core/Error.h"
#include "gpu/Bindings.h"
#include "gpu/Program.h"
#include "render/SceneDrawer.h"
#include "techniques/screen_voxels/screen_voxels_shared.h"

namespace bounce::voxels {

struct GridSize {
    glm::ivec2 columns{128};  // x/y resolution (thesis: 128^2 .. 1024^2; 128^2 "almost indistinguishable")
    int bits = 128;           // depth bits per column, a multiple of 128 (thesis: 128; "up to 2048")
    // Each fragment sets every slice its triangle spans within the pixel (bounce's default) instead of
    // the one slice at the pixel centre (the thesis); see voxelize.frag.
    bool footprint = true;
};

// Checks a grid size: columns positive, bits a positive multiple of 128 and at most 128 x the GPU's
// draw buffers (8 in GL 4.5's minimum, so 1024 bits). Errors name the setting names given.
Expected<void> checkGrid(const GridSize& size, std::string_view columnsName, std::string_view bitsName);

class ScreenVoxels {
public:
    static Expected<ScreenVoxels> create();

    // Voxelizes the scene as `camera` sees it. The depth range is the scene's bounds at the current
    // time in view space, widened by half a slice each side so the bounds' faces fall on slice centres,
    // and clipped to the camera's near and far planes (slices are wasted on nothing outside the scene;
    // an assumption, the thesis does not say).
    void build(render::SceneDrawer& drawer, const render::View& camera, const GridSize& size);
    // Binds the grid for march.glsl: at BINDING_UBO_VOXELS and BINDING_TEX_VOXELS (the grid it marches),
    // or at other points (a second grid, march.glsl SV_OUTER_GRID). build() leaves the grid bound at
    // BINDING_UBO_VOXELS.
    void bind(unsigned uboBinding = BINDING_UBO_VOXELS, unsigned textureUnit = BINDING_TEX_VOXELS) const;
    const gpu::ScreenVoxelsGpu& uniforms() const { return m_uniforms; }
    const gl::Texture& bitsTexture() const { return m_bits; }
    // Occupied voxels (a CPU read-back of every column's popcount: for tests, not per frame).
    uint64_t countOccupied() const;

private:
    gl::Program m_program;
    gl::Texture m_bits;  // RGBA32UI 2D array, one layer per 128 bits
    gl::Framebuffer m_fbo;
    gl::Buffer m_ubo;
    gpu::ScreenVoxelsGpu m_uniforms{};
    GridSize m_allocated{glm::ivec2(0), 0};
};

}  // namespace bounce::voxels
