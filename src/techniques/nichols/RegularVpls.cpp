#include "techniques/nichols/RegularVpls.h"

#include "core/Check.h"
#include "gpu/Bindings.h"
#include "gpu/Context.h"
#include "gpu/SetupLimits.h"
#include "gpu/ShaderLimits.h"
#include "techniques/nichols/VplWindow.h"

namespace bounce::nichols {

namespace {
constexpr int kLocalSize = 8;  // vpl_extract.comp local_size_x/y
}

Expected<RegularVpls> RegularVpls::create() {
    RegularVpls r;
    BOUNCE_TRY(r.m_program, gl::Program::build({"nichols.vplExtract",
                                                {{GL_COMPUTE_SHADER, "techniques/nichols/vpl_extract.comp"}}}));
    return r;
}

Expected<void> RegularVpls::checkGrid(int rsmSize, int grid, int layers) {
    if (grid <= 0 || rsmSize % grid != 0) return makeError("setting vplGrid={} does not divide rsmSize={}", grid, rsmSize);
    const size_t records = static_cast<size_t>(grid) * static_cast<size_t>(grid) * static_cast<size_t>(layers);
    const size_t bytes = (records + static_cast<size_t>(VplWindow::size())) * sizeof(VplRecord);  // with the window padding
    BOUNCE_TRY_VOID(gl::checkStorageBuffer(gl::Context::current()->info(), bytes, fmt::format("setting vplGrid={}", grid),
                                           fmt::format("the VPL cache of {} VPLs ({} RSM layers)", records, layers)));
    // The extraction loops over a block's texels (and once per block row): block^2 + block iterations.
    const int block = rsmSize / grid;
    if (block * block + block > gl::shaderLoopIterationBudget()) {
        int smallest = grid;
        while (rsmSize / smallest * (rsmSize / smallest) + rsmSize / smallest > gl::shaderLoopIterationBudget() ||
               rsmSize % smallest != 0)
            ++smallest;
        return makeError("setting vplGrid={} with rsmSize={}: blocks of {}x{} RSM texels per VPL exceed the shader loop "
                         "budget of {} iterations; use vplGrid >= {}",
                         grid, rsmSize, block, block, gl::shaderLoopIterationBudget(), smallest);
    }
    return {};
}

void RegularVpls::extract(const ReflectiveShadowMap& rsm, int grid) {
    BOUNCE_CHECK(rsm.valid(), "VPL extraction without a rendered RSM");
    BOUNCE_CHECK(grid > 0 && grid <= rsm.size() && rsm.size() % grid == 0, "VPL grid {} does not divide the RSM size {}",
                 grid, rsm.size());
    const int count = grid * grid * rsm.layers();
    // Padded to a whole uniform-block window past the last VPL (VplWindow::bind; issue 29 #13).
    const size_t bytes = static_cast<size_t>(VplWindow::paddedRecords(count)) * sizeof(VplRecord);
    if (!m_buffer || m_buffer.size() != bytes) m_buffer = gl::Buffer::create("nichols.vplCache", bytes);
    m_count = count;
    if (grid != m_grid || rsm.layers() != m_layers) {
        m_grid = grid;
        m_layers = rsm.layers();
        const gl::TextureDesc d = texelArrayDesc(grid, m_layers);
        m_position = gl::Texture::create("nichols.vplCache.position", d);
        m_normal = gl::Texture::create("nichols.vplCache.normal", d);
        m_flux = gl::Texture::create("nichols.vplCache.flux", d);
    }
    m_position.bindImage(BINDING_IMG0, GL_WRITE_ONLY, 0, true);
    m_normal.bindImage(BINDING_IMG1, GL_WRITE_ONLY, 0, true);
    m_flux.bindImage(BINDING_IMG2, GL_WRITE_ONLY, 0, true);
    rsm.position().bind(BINDING_TEX_TECH0);
    rsm.normal().bind(BINDING_TEX_TECH1);
    rsm.flux().bind(BINDING_TEX_TECH2);
    m_buffer.bindBase(GL_SHADER_STORAGE_BUFFER, BINDING_SSBO_TECH0);
    m_program.set("u_grid", grid);
    m_program.set("u_block", rsm.size() / grid);
    m_program.use();
    const int groups = (grid + kLocalSize - 1) / kLocalSize;
    glDispatchCompute(static_cast<GLuint>(groups), static_cast<GLuint>(groups), static_cast<GLuint>(rsm.layers()));
    glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT | GL_TEXTURE_FETCH_BARRIER_BIT | GL_UNIFORM_BARRIER_BIT);
}

std::vector<VplRecord> RegularVpls::download() const {
    std::vector<VplRecord> v(static_cast<size_t>(m_count));
    // vpl_extract.comp wrote the cache as a storage buffer: the CPU read needs this bit (issue 29 #7).
    glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
    if (m_count > 0) m_buffer.download(0, v.size() * sizeof(VplRecord), v.data());
    return v;
}

}  // namespace bounce::nichols
