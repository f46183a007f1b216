#pragma once
// CPU references of the isotropic and anisotropic mip filters of Rauwendaal 2013 section 5.3, and
// the RGBA8 running average of Fig. B.1, GL-free. Children are indexed as in ShMath.h (bit 0 = +x
// half, bit 1 = +y, bit 2 = +z); faces 0..5 = +X, -X, +Y, -Y, +Z, -Z.
//
// Colour convention: every voxel value here is (straight colour rgb, opacity a); an empty voxel is
// (0, 0, 0, 0) and level 0 is opaque (a = 1, thesis 5.1.1).
#include <glm/vec3.hpp>
#include <glm/vec4.hpp>

#include <array>
#include <cstdint>

namespace bounce::vct {

// Section 5.3.1, "average voxel color values as weighted by their opacity":
//   parent.rgb = sum a_i c_i / sum a_i   (0 when every child is empty),
//   parent.a   = sum a_i / 8             (the mean: opacity is averaged, which is what turns opaque
//                                         walls partly transparent at coarse levels, as 5.3.1 says).
// This is the box filter of premultiplied (a c, a) followed by un-premultiplying, so the colour of
// a half-empty block is the colour of its occupied half, not a darkened one. It is the same
// convention as the SH mip, which averages over the active children only and keeps opacity in a
// separate volume (Eq. 5.9, Fig. B.3).
glm::vec4 isotropicMipParent(const std::array<glm::vec4, 8>& children);

// Section 5.3.2 ([CNS*11], [Yeu13]; spec 2.8 / 2.9 inferences). Face d of an anisotropic voxel holds
// the value seen when looking along direction d, i.e. by a ray travelling along d (the sampler of
// Fig. B.2 reads face +X for a cone whose direction has x >= 0). For face d the 8 children form 4
// pairs along d's axis; the child met first by such a ray is "near":
//   face +X: near = the -x child (bit 0 clear), far = the +x child;  face -X: near = the +x child;
//   likewise +Y / -Y with bit 1 and +Z / -Z with bit 2.
// Each pair is composited front to back on premultiplied values using the children's face-d values,
//   C = a_n c_n + (1 - a_n) a_f c_f,   A = a_n + (1 - a_n) a_f,
// (c = c_near + (1 - a_near) c_far in premultiplied form), the 4 pairs are averaged, and the result
// is returned straight as above: rgb = sum C / sum A, a = sum A / 4.
using AnisoVoxel = std::array<glm::vec4, 6>;
AnisoVoxel anisotropicMipParent(const std::array<AnisoVoxel, 8>& children);
// The child index that is near (first along the viewing direction) for face `face` in the pair
// whose other two bits are those of `pairBits` (the face axis bit of pairBits is ignored).
int anisoNearChild(int face, int pairBits);
// Level 0 of the thesis's comparisons: the isotropic value duplicated to all 6 faces (5.1.2).
AnisoVoxel anisoFromIsotropic(glm::vec4 v);

// Fig. B.1 packing: r, g, b in bytes 0..2 and the write count in byte 3; v holds values in 0..255.
// Deviations from the printed code (as shaders/techniques/vct/volume.glsl does): each component is
// clamped to [0, 255] instead of masked with & 0xFF (which wraps), and r, g, b are rounded to the
// nearest integer instead of truncated (truncation biases every rewrite down by up to 1/255).
uint32_t packRgbCount(glm::vec4 v);
glm::vec4 unpackRgbCount(uint32_t v);
// One successful compare-and-swap of Fig. B.1: the stored value `prev` (0 = never written) updated
// with the colour `next` in [0, 1]: average = (avg * count + next) / (count + 1), count + 1. The count
// saturates at 255 (the printed code wraps it to 0 after 255 writes, restarting the average).
uint32_t averageRgba8(uint32_t prev, glm::vec3 next);

}  // namespace bounce::vct
