// The voxel volumes of Rauwendaal 2013 ch. 5 as images, and the writes of the voxelizers (section
// 5.1): isotropic RGBA8 through an r32ui view with imageAtomicMax or the compare-and-swap running
// average of Fig. B.1; 12 x R32F spherical harmonics by float atomic add (NV_shader_atomic_float,
// VCT_FLOAT_ATOMICS; else a compare-and-swap loop) plus a write count for the normalisation pass; the binary occupancy volume of Table 4.1; and the
// active-voxel list of level 0 (section 5.4: a mutex volume claimed with imageAtomicCompSwap, an
// atomic append). Radiance is stored divided by u_vct.range.x in the 8-bit formats.
// Inputs: u_vct (BINDING_UBO_PASS). Images: BINDING_IMG0 iso (r32ui), IMG1..3 SH DC r/g/b (r32f),
// IMG4 write count (r32ui), IMG5 binary occupancy (r8ui), IMG6 level-0 mutex (r32ui).
#ifndef BOUNCE_VCT_VOLUME_GLSL
#define BOUNCE_VCT_VOLUME_GLSL
#include "techniques/vct/vct_shared.h"

layout(std140, binding = BINDING_UBO_PASS) uniform VctBlock { VctUniforms u_vct; };

// Active-voxel list entries: 10 bits per coordinate (N <= 512).
uint packVoxel(ivec3 p) { return uint(p.x) | (uint(p.y) << 10) | (uint(p.z) << 20); }
ivec3 unpackVoxel(uint v) { return ivec3(v & 1023u, (v >> 10) & 1023u, (v >> 20) & 1023u); }

#ifdef VCT_WRITE
// Counters: [0] voxel writes, [1] triangles voxelized in the geometry shader (pass 1),
// [2] triangles deferred to pass 2, [3] writes dropped by a compare-and-swap loop that lost
// VCT_CAS_RETRIES races in a row (issue 29 #18; the counter casDrops); [4..7] pass 2's indirect command;
// [8] triangles whose voxel box may pass the loop budget in one geometry-shader invocation (#10).
layout(std430, binding = BINDING_SSBO_TECH1) coherent buffer VctCounters { uint c_counts[12]; };
#ifndef VCT_CAS_RETRIES
#define VCT_CAS_RETRIES 255
#endif
void countCasDrop() { atomicAdd(c_counts[3], 1u); }
layout(binding = BINDING_IMG0, r32ui) uniform coherent volatile uimage3D i_iso;
#if VCT_STORAGE == VCT_STORAGE_SH_F32
#if VCT_FLOAT_ATOMICS
layout(binding = BINDING_IMG1, r32f) uniform coherent image3D i_shR;
layout(binding = BINDING_IMG2, r32f) uniform coherent image3D i_shG;
layout(binding = BINDING_IMG3, r32f) uniform coherent image3D i_shB;
void addSh(int c, ivec3 p, float v) {
    if (c == 0) imageAtomicAdd(i_shR, p, v);
    else if (c == 1) imageAtomicAdd(i_shG, p, v);
    else imageAtomicAdd(i_shB, p, v);
}
#else
// Without GL_NV_shader_atomic_float (AMD, Intel): the R32F volumes bound through r32ui views and the
// float added by a compare-and-swap loop on its bits (bounded like Fig. B.1's; a write that loses
// VCT_CAS_RETRIES races in a row is dropped and counted, casDrops).
layout(binding = BINDING_IMG1, r32ui) uniform coherent uimage3D i_shR;
layout(binding = BINDING_IMG2, r32ui) uniform coherent uimage3D i_shG;
layout(binding = BINDING_IMG3, r32ui) uniform coherent uimage3D i_shB;
uint casAdd(uint current, float v) { return floatBitsToUint(uintBitsToFloat(current) + v); }
void addSh(int c, ivec3 p, float v) {
    uint current = c == 0 ? imageLoad(i_shR, p).r : (c == 1 ? imageLoad(i_shG, p).r : imageLoad(i_shB, p).r);
    for (int i = 0; i < VCT_CAS_RETRIES; ++i) {
        uint previous = c == 0 ? imageAtomicCompSwap(i_shR, p, current, casAdd(current, v))
                      : (c == 1 ? imageAtomicCompSwap(i_shG, p, current, casAdd(current, v))
                                : imageAtomicCompSwap(i_shB, p, current, casAdd(current, v)));
        if (previous == current) return;
        current = previous;
    }
    countCasDrop();
}
#endif
layout(binding = BINDING_IMG4, r32ui) uniform coherent uimage3D i_count;
#endif
layout(binding = BINDING_IMG5, r8ui) uniform writeonly uimage3D i_binary;
layout(binding = BINDING_IMG6, r32ui) uniform coherent uimage3D i_mutex;

// Active-voxel list of level 0 (head: count, three free words, capacity; then packed coordinates).
layout(std430, binding = BINDING_SSBO_TECH0) coherent buffer ActiveList0 {
    uint a_count, a_unused0, a_unused1, a_unused2;
    uint a_capacity, a_pad0, a_pad1, a_pad2;
    uint a_voxels[];
};

uint packRgbCount(vec4 v) {
    uvec4 u = uvec4(clamp(v, vec4(0.0), vec4(255.0)) + vec4(0.5, 0.5, 0.5, 0.0));
    return u.r | (u.g << 8) | (u.b << 16) | (u.a << 24);
}
vec4 unpackRgbCount(uint v) { return vec4(v & 0xFFu, (v >> 8) & 0xFFu, (v >> 16) & 0xFFu, (v >> 24) & 0xFFu); }

// Fig. B.1 (after Crassin & Green 2012): the running average of the colours written to a voxel, the
// count in the top byte. Converges because every retry re-reads the value that beat it.
void imageAtomicAverageRgba8(ivec3 p, vec3 value01) {
    uint next = packRgbCount(vec4(value01 * 255.0, 1.0));
    uint current = 0u;
    uint previous;
    // Bounded: under contention each retry makes progress for one writer; 255 retries (casRetries'
    // default) is far more than the writes one voxel receives in a frame (and the count saturates at
    // 255 anyway). A write that loses them all is dropped and counted (casDrops).
    for (int i = 0; i < VCT_CAS_RETRIES; ++i) {
        previous = imageAtomicCompSwap(i_iso, p, current, next);
        if (previous == current) return;
        current = previous;
        vec4 c = unpackRgbCount(current);
        float count = c.a;
        vec3 average = (c.rgb / 255.0 * count + value01) / (count + 1.0);
        next = packRgbCount(vec4(average * 255.0, min(count + 1.0, 255.0)));
    }
    countCasDrop();
}

// One voxel p (unswizzled) of a surface reflecting `radiance` W/(m^2 sr).
void writeVoxel(ivec3 p, vec3 radiance) {
    atomicAdd(c_counts[0], 1u);
    if (u_vct.debug.w > 0.5 && imageAtomicCompSwap(i_mutex, p, 0u, 1u) == 0u) {
        uint slot = atomicAdd(a_count, 1u);
        if (slot < a_capacity) a_voxels[slot] = packVoxel(p);
    }
    if (u_vct.range.w > 0.5) {
        imageStore(i_binary, p, uvec4(1u));
        return;
    }
    vec3 scaled = clamp(radiance / u_vct.range.x, vec3(0.0), vec3(1.0));
    if (int(u_vct.voxelize.w + 0.5) == VCT_ATOMIC_AVERAGE) {
        imageAtomicAverageRgba8(p, scaled);
    } else {
        // The alpha byte is the most significant of the r32ui view of RGBA8 (little-endian), so the
        // max compares opacity first without the thesis's ARGB swizzle; level-0 alpha is always 1.
        imageAtomicMax(i_iso, p, packRgbCount(vec4(scaled * 255.0, 255.0)));
    }
#if VCT_STORAGE == VCT_STORAGE_SH_F32
    // Level 0 is isotropic (thesis 5.1.3: normal-initialised SH darkened the hierarchy): only the DC
    // terms receive writes; the sum of radiances is divided by the count in the normalisation pass.
    addSh(0, p, radiance.r);
    addSh(1, p, radiance.g);
    addSh(2, p, radiance.b);
    imageAtomicAdd(i_count, p, 1u);
#endif
}
#endif

#endif
