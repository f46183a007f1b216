#pragma once
// CPU references of the isotropic and anisotropic mip filters of Rauwendaal 2013 section 5.3, and
// the RGBA8 running average of Fig. B.1, GL-free. Children are indexed as in ShMath.h (bit 0 = +x
// half, bit 1 = +y, bit 2 = +z); faces 0..5 = +X, -X, +Y, -Y, +Z, -Z.
//
// Colour convention, the GPU's (shaders/techniques/vct/passes.glsl): every voxel value is
// (colour premultiplied by opacity, opacity); an empty voxel is (0, 0, 0, 0) and level 0 is opaque
// (a = 1, thesis 5.1.1), where premultiplied and straight colour agree. Premultiplied values are what
// textureLod may filter across occupied and empty voxels and what Fig. B.4's compositing
// accum += (1 - accum.a) sample assumes.
#include <glm/vec3.hpp>
#include <glm/vec4.hpp>

#include <array>
#include <cstdint>

namespace bounce::vct {

// Section 5.3.1, "average voxel color values as weighted by their opacity", on premultiplied values:
//   parent = sum (a_i c_i, a_i) / 8,
// i.e. the opacity-weighted average colour sum a_i c_i / sum a_i times the mean opacity sum a_i / 8 (the
// averaged opacity is what turns opaque walls partly transparent at coarse levels, as 5.3.1 says).
glm::vec4 isotropicMipParent(const std::array<glm::vec4, 8>& children);

// Section 5.3.2 ([CNS*11], [Yeu13]; spec 2.8 / 2.9 inferences). Face d of an anisotropic voxel holds
// the value seen when looking along direction d, i.e. by a ray travelling along d (the sampler of
// Fig. B.2 reads face +X for a cone whose direction has x >= 0). For face d the 8 children form 4
// pairs along d's axis; the child met first by such a ray is "near":
//   face +X: near = the -x child (bit 0 clear), far = the +x child;  face -X: near = the +x child;
//   likewise +Y / -Y with bit 1 and +Z / -Z with bit 2.
// Each pair is composited front to back on premultiplied values using the children's face-d values,
//   (C, A) = (c_n + (1 - a_n) c_f, a_n + (1 - a_n) a_f),
// and the 4 pairs are averaged (premultiplied, as stored).
using AnisoVoxel = std::array<glm::vec4, 6>;
AnisoVoxel anisotropicMipParent(const std::array<AnisoVoxel, 8>& children);
// The child index that is near (first along the viewing direction) for face `face` in the pair
// whose other two bits are those of `pairBits` (the face axis bit of pairBits is ignored).
int anisoNearChild(int face, int pairBits);
// Level 0 of the thesis's comparisons: the isotropic value duplicated to all 6 faces (5.1.2).
AnisoVoxel anisoFromIsotropic(glm::vec4 v);

uint32_t packRgbCount(glm::vec4 v);
glm::vec4 unpackRgbCount(uint32_t v);
// One successful compare-and-swap of Fig. B.1: the stored value `prev` (0 = never written) updated
// with the colour `next` in [0, 1]: average = (avg * count + next) / (count + 1), count + 1. The count
// saturates at 255 (the printed code wraps it to 0 after 255 writes, restarting the average).
uint32_t averageRgba8(uint32_t prev, glm::vec3 next);

}  // namespace bounce::vct
