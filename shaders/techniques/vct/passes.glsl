// Rauwendaal 2013 sections 5.1, 5.3, 5.4: the passes after voxelization, one voxel per invocation.
//   VCT_PASS 1 post-voxelization (level 0): the average's write count -> opacity 1 (isotropic, thesis
//              5.1.1 "base level voxels are opaque"); SH-F32 normalisation (sum / count, projected on
//              Y00); SH-U8 transfer of the isotropic result into 3 x RGBA8 (SNORM here, see vct.md).
//   VCT_PASS 2 isotropic mip (5.3.1): colour averaged weighted by opacity, opacity averaged. Every
//              format runs it: its alpha is the opacity the SH samplers read. In the sparse path the
//              invocation is a child of the active list of level u_level - 1 that claims its parent
//              (mutex volume, imageAtomicCompSwap) and appends it to the next list.
//   VCT_PASS 3 anisotropic mip (5.3.2, after Crassin et al. 2011): per face direction, the four child
//              pairs along it composited front to back, then averaged.
//   VCT_PASS 4 SH mip of colour channel u_channel (5.3.3, Eq. 5.9): each child projected on the six
//              faces of its parent (solid angles 3.114 / 1.075 sr), re-emitted as clamped cosine lobes,
//              summed, divided by pi (the normalisation the thesis leaves out: without it each level
//              multiplies radiance by pi) and by 8. The thesis divides by the number of active children
//              (straight colour, its sampler then reads opacity from the alpha volume); here the
//              coefficients are premultiplied by opacity like the isotropic colours, so that filtering
//              between occupied and empty voxels does not darken twice (docs/techniques/vct.md). Level 0
//              (opacity 0 or 1) is the same in both conventions.
//   VCT_PASS 5 sparse clear (bounce; section 5.4 leaves clearing open): the voxels the previous frame
//              listed at level u_level are zeroed in the isotropic volume, the mutex and up to six
//              radiance volumes (u_volumeCount), so that the sparse path never clears a dense level.
// The voxel comes from voxelCoordinate() (dense: the invocation; sparse: the active list).
#include "techniques/vct/volume.glsl"
#include "techniques/vct/sh.glsl"

uniform int u_level;    // level written (0 for the post pass)
uniform int u_channel;  // SH mip: 0 r, 1 g, 2 b

layout(binding = BINDING_TEX_VCT_ALPHA) uniform sampler3D s_alpha;
layout(binding = BINDING_TEX_VCT_VOLUME0) uniform sampler3D s_vol[12];

layout(std430, binding = BINDING_SSBO_TECH0) coherent buffer ListIn {
    uint in_count, in_unused0, in_unused1, in_unused2;  // words 1-3: free since the list is dispatched, not drawn
    uint in_capacity, in_pad0, in_pad1, in_pad2;
    uint in_voxels[];
};
layout(std430, binding = BINDING_SSBO_TECH2) coherent buffer ListOut {
    uint out_count, out_unused0, out_unused1, out_unused2;
    uint out_capacity, out_pad0, out_pad1, out_pad2;
    uint out_voxels[];
};


ivec3 childOf(ivec3 parent, int i) { return 2 * parent + ivec3(i & 1, (i >> 1) & 1, (i >> 2) & 1); }

#if VCT_PASS == 1
layout(binding = BINDING_IMG0, r32ui) uniform coherent uimage3D i_iso;
#if VCT_STORAGE == VCT_STORAGE_SH_F32
layout(binding = BINDING_IMG1, r32f) uniform image3D i_sh0;
layout(binding = BINDING_IMG2, r32f) uniform image3D i_sh1;
layout(binding = BINDING_IMG3, r32f) uniform image3D i_sh2;
layout(binding = BINDING_IMG4, r32ui) uniform uimage3D i_count;
#elif VCT_STORAGE == VCT_STORAGE_SH_U8
layout(binding = BINDING_IMG1, rgba8_snorm) uniform writeonly image3D i_sh0;
layout(binding = BINDING_IMG2, rgba8_snorm) uniform writeonly image3D i_sh1;
layout(binding = BINDING_IMG3, rgba8_snorm) uniform writeonly image3D i_sh2;
#endif

void processVoxel(ivec3 p) {
    uint word = imageLoad(i_iso, p).r;
    if ((word >> 24) == 0u) return;  // empty
    if (int(u_vct.voxelize.w + 0.5) == VCT_ATOMIC_AVERAGE) imageStore(i_iso, p, uvec4(word | 0xFF000000u));
#if VCT_STORAGE == VCT_STORAGE_SH_F32
    float count = float(imageLoad(i_count, p).r);
    if (count > 0.0) {
        float scale = 1.0 / (count * kShY00);
        imageStore(i_sh0, p, vec4(imageLoad(i_sh0, p).r * scale));
        imageStore(i_sh1, p, vec4(imageLoad(i_sh1, p).r * scale));
        imageStore(i_sh2, p, vec4(imageLoad(i_sh2, p).r * scale));
    }
#elif VCT_STORAGE == VCT_STORAGE_SH_U8
    vec3 radiance = vec3(word & 0xFFu, (word >> 8) & 0xFFu, (word >> 16) & 0xFFu) / 255.0 * u_vct.range.x;
    vec3 dc = radiance / (kShY00 * u_vct.range.y);
    imageStore(i_sh0, p, vec4(dc.r, 0.0, 0.0, 0.0));
    imageStore(i_sh1, p, vec4(dc.g, 0.0, 0.0, 0.0));
    imageStore(i_sh2, p, vec4(dc.b, 0.0, 0.0, 0.0));
#endif
}

#elif VCT_PASS == 2
layout(binding = BINDING_IMG0, rgba8) uniform writeonly image3D i_isoOut;
layout(binding = BINDING_IMG7, r32ui) uniform coherent uimage3D i_mutexOut;

void mipIso(ivec3 q) {
    vec3 colour = vec3(0.0);
    float alpha = 0.0;
    for (int i = 0; i < 8; ++i) {
        vec4 c = texelFetch(s_alpha, childOf(q, i), u_level - 1);
        colour += c.rgb;  // premultiplied
        alpha += c.a;
    }
    // Stored premultiplied by opacity: sum(alpha_i c_i) / 8 is the opacity-weighted average
    // sum(alpha_i c_i) / sum(alpha_i) times the parent's opacity sum(alpha_i) / 8. Level 0 (opacity 0
    // or 1) is both. Fig. B.4 composites accum += (1 - accum.a) * sample on colour and opacity alike,
    // which is correct for premultiplied samples only (non-premultiplied ones count a half-empty
    // voxel's colour in full at every step: measured 3x too bright on cornell-box).
    imageStore(i_isoOut, q, vec4(colour / 8.0, alpha / 8.0));
}

void processVoxel(ivec3 p) {
#if VCT_SPARSE
    // p is an active child: the first child to claim the parent computes it and lists it.
    ivec3 q = p >> 1;
    if (imageAtomicCompSwap(i_mutexOut, q, 0u, 1u) != 0u) return;
    uint slot = atomicAdd(out_count, 1u);
    if (slot < out_capacity) out_voxels[slot] = packVoxel(q);
    mipIso(q);
#else
    mipIso(p);
#endif
}

#elif VCT_PASS == 3
layout(binding = BINDING_IMG0, rgba8) uniform writeonly image3D i_face0;
layout(binding = BINDING_IMG1, rgba8) uniform writeonly image3D i_face1;
layout(binding = BINDING_IMG2, rgba8) uniform writeonly image3D i_face2;
layout(binding = BINDING_IMG3, rgba8) uniform writeonly image3D i_face3;
layout(binding = BINDING_IMG4, rgba8) uniform writeonly image3D i_face4;
layout(binding = BINDING_IMG5, rgba8) uniform writeonly image3D i_face5;

// Face f (0 +X, 1 -X, 2 +Y, 3 -Y, 4 +Z, 5 -Z) holds what is seen looking along that direction
// (the sampler picks the face by the cone direction, Fig. B.2): looking along +X the child with the
// smaller x is met first.
vec4 faceValue(ivec3 q, int f) {
    int axis = f >> 1;
    bool positive = (f & 1) == 0;
    vec4 sum = vec4(0.0);
    for (int pair = 0; pair < 4; ++pair) {
        // the two bits other than `axis`
        ivec3 o = ivec3(0);
        int k = 0;
        for (int a = 0; a < 3; ++a) {
            if (a == axis) continue;
            o[a] = (pair >> k) & 1;
            ++k;
        }
        ivec3 nearC = 2 * q + o, farC = 2 * q + o;
        nearC[axis] += positive ? 0 : 1;
        farC[axis] += positive ? 1 : 0;
        vec4 n = texelFetch(s_vol[f], nearC, u_level - 1);
        vec4 fa = texelFetch(s_vol[f], farC, u_level - 1);
        sum += n + (1.0 - n.a) * fa;
    }
    return sum * 0.25;
}

void processVoxel(ivec3 q) {
    imageStore(i_face0, q, faceValue(q, 0));
    imageStore(i_face1, q, faceValue(q, 1));
    imageStore(i_face2, q, faceValue(q, 2));
    imageStore(i_face3, q, faceValue(q, 3));
    imageStore(i_face4, q, faceValue(q, 4));
    imageStore(i_face5, q, faceValue(q, 5));
}

#elif VCT_PASS == 4
#if VCT_STORAGE == VCT_STORAGE_SH_F32
layout(binding = BINDING_IMG0, r32f) uniform writeonly image3D i_c0;
layout(binding = BINDING_IMG1, r32f) uniform writeonly image3D i_c1;
layout(binding = BINDING_IMG2, r32f) uniform writeonly image3D i_c2;
layout(binding = BINDING_IMG3, r32f) uniform writeonly image3D i_c3;
#else
layout(binding = BINDING_IMG0, rgba8_snorm) uniform writeonly image3D i_c0;
#endif

vec4 childSh(ivec3 c) {
#if VCT_STORAGE == VCT_STORAGE_SH_F32
    int base = 4 * u_channel;
    return vec4(texelFetch(s_vol[base], c, u_level - 1).r, texelFetch(s_vol[base + 1], c, u_level - 1).r,
                texelFetch(s_vol[base + 2], c, u_level - 1).r, texelFetch(s_vol[base + 3], c, u_level - 1).r);
#else
    return texelFetch(s_vol[u_channel], c, u_level - 1) * u_vct.range.y;
#endif
}

// Eq. 5.9 is linear in a child's coefficients V: the six-face sum for the child in octant i,
// sum_f Omega_f <SH(d_if), V> SH_cos(d_if), is the fixed matrix u_shMip[i] V (built on the CPU from
// the same formula, techniques/vct/ShMath.cpp; the GPU test compares this pass with the literal
// per-face sum).
uniform mat4 u_shMip[8];

void processVoxel(ivec3 q) {
    vec4 sum = vec4(0.0);
    for (int i = 0; i < 8; ++i) sum += u_shMip[i] * childSh(childOf(q, i));  // empty children are 0
    // Premultiplied: sum_i alpha_i P_i / 8, the children's coefficients already carrying alpha_i.
    vec4 parent = sum / (8.0 * kPi);
#if VCT_STORAGE == VCT_STORAGE_SH_F32
    imageStore(i_c0, q, vec4(parent.x));
    imageStore(i_c1, q, vec4(parent.y));
    imageStore(i_c2, q, vec4(parent.z));
    imageStore(i_c3, q, vec4(parent.w));
#else
    imageStore(i_c0, q, parent / u_vct.range.y);
#endif
}
#elif VCT_PASS == 5
layout(binding = BINDING_IMG0, rgba8) uniform writeonly image3D i_clearIso;
layout(binding = BINDING_IMG1, r32ui) uniform writeonly uimage3D i_clearMutex;
#if VCT_STORAGE == VCT_STORAGE_SH_F32
#define VCT_CLEAR_FORMAT r32f
#elif VCT_STORAGE == VCT_STORAGE_SH_U8
#define VCT_CLEAR_FORMAT rgba8_snorm
#else
#define VCT_CLEAR_FORMAT rgba8
#endif
layout(binding = BINDING_IMG2, VCT_CLEAR_FORMAT) uniform writeonly image3D i_clear0;
layout(binding = BINDING_IMG3, VCT_CLEAR_FORMAT) uniform writeonly image3D i_clear1;
layout(binding = BINDING_IMG4, VCT_CLEAR_FORMAT) uniform writeonly image3D i_clear2;
layout(binding = BINDING_IMG5, VCT_CLEAR_FORMAT) uniform writeonly image3D i_clear3;
layout(binding = BINDING_IMG6, VCT_CLEAR_FORMAT) uniform writeonly image3D i_clear4;
layout(binding = BINDING_IMG7, VCT_CLEAR_FORMAT) uniform writeonly image3D i_clear5;
uniform int u_volumeCount;  // radiance volumes bound at IMG2.. (0..6)

void processVoxel(ivec3 p) {
    imageStore(i_clearIso, p, vec4(0.0));
    imageStore(i_clearMutex, p, uvec4(0u));
    if (u_volumeCount > 0) imageStore(i_clear0, p, vec4(0.0));
    if (u_volumeCount > 1) imageStore(i_clear1, p, vec4(0.0));
    if (u_volumeCount > 2) imageStore(i_clear2, p, vec4(0.0));
    if (u_volumeCount > 3) imageStore(i_clear3, p, vec4(0.0));
    if (u_volumeCount > 4) imageStore(i_clear4, p, vec4(0.0));
    if (u_volumeCount > 5) imageStore(i_clear5, p, vec4(0.0));
}
#endif
