// vct's read-backs for tests, counters and debug tools: the allocated bytes per voxel of its volumes
// (as GL reports the formats' component sizes, not as the settings say) and level-by-level downloads
// of the occupancy, the isotropic volume and the radiance volumes. Kept apart from the frame's passes
// in VctTechnique.cpp; nothing here runs in a frame but collectCounters' byte counts.
#include "techniques/vct/VctTechnique.h"

#include "gpu/Bindings.h"

namespace bounce {

namespace {
// Bytes of one level-0 texel of `t` as allocated: the component sizes GL reports for its format.
double texelBytes(const gl::Texture& t) {
    GLint bits = 0;
    for (GLenum q : {GL_TEXTURE_RED_SIZE, GL_TEXTURE_GREEN_SIZE, GL_TEXTURE_BLUE_SIZE, GL_TEXTURE_ALPHA_SIZE}) {
        GLint b = 0;
        glGetTextureLevelParameteriv(t.id(), 0, q, &b);
        bits += b;
    }
    return bits / 8.0;
}
}  // namespace

double VctTechnique::allocatedRadianceBytesPerVoxel() const {
    if (m_binary) return texelBytes(m_binaryVolume);
    // The isotropic format's radiance is its RGBA8 volume; the other formats keep it as their alpha.
    if (storageId() == VCT_STORAGE_ISO) return texelBytes(m_iso);
    double bytes = 0.0;
    for (const gl::Texture& v : m_volumes) bytes += texelBytes(v);
    return bytes;
}

double VctTechnique::allocatedAlphaBytesPerVoxel() const {
    return (m_binary || storageId() == VCT_STORAGE_ISO) ? 0.0 : texelBytes(m_iso);
}

std::vector<uint8_t> VctTechnique::downloadOccupancy() const {
    const size_t n = static_cast<size_t>(m_resolution) * m_resolution * m_resolution;
    std::vector<uint8_t> out(n);
    if (m_binary) {
        glGetTextureImage(m_binaryVolume.id(), 0, GL_RED_INTEGER, GL_UNSIGNED_BYTE, static_cast<GLsizei>(n), out.data());
        return out;
    }
    std::vector<uint32_t> iso = downloadIso(0);
    for (size_t i = 0; i < n; ++i) out[i] = (iso[i] >> 24) != 0 ? 1 : 0;
    return out;
}

std::vector<uint32_t> VctTechnique::downloadIso(int level) const {
    const size_t side = static_cast<size_t>(m_resolution >> level);
    std::vector<uint32_t> out(side * side * side);
    glGetTextureImage(m_iso.id(), level, GL_RGBA, GL_UNSIGNED_BYTE, static_cast<GLsizei>(out.size() * 4), out.data());
    return out;
}

std::vector<float> VctTechnique::downloadVolume(int index, int level) const {
    const size_t side = static_cast<size_t>(m_resolution >> level);
    const bool single = storageId() == VCT_STORAGE_SH_F32;
    std::vector<float> out(side * side * side * (single ? 1 : 4));
    glGetTextureImage(m_volumes.at(static_cast<size_t>(index)).id(), level, single ? GL_RED : GL_RGBA, GL_FLOAT,
                      static_cast<GLsizei>(out.size() * sizeof(float)), out.data());
    return out;
}

}  // namespace bounce
