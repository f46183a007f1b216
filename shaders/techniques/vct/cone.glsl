// Rauwendaal 2013 ch. 6: voxel cone tracing over the mipmapped volumes.
//   voxelFetch (section 5.2, Figs. B.2-B.3): isotropic fetch; the ambient cube of the six anisotropic
//     faces weighted by the squared cone direction; 2-band SH evaluated at -dir (clamped at 0: the
//     thesis clamps to [0, 1] for its LDR colours, radiance here is HDR), times the opacity (the
//     samples are composited as premultiplied colours, Fig. B.4). Quadrilinear: textureLod
//     with a fractional level. Returns (radiance W/(m^2 sr), opacity).
//   coneTrace (Fig. B.4): the generic tracer, cone ratio sin(theta/2) / (1 - sin(theta/2)), sample
//     diameter >= one voxel, LOD = log2(diameter N), front-to-back accumulation, exit at opacity 1 or
//     maxDist, AO frozen at aoDist.
//   coneTrace60 (Fig. B.5): the specialised 60-degree diffuse tracer sampling at integer LODs,
//     distance doubling from one voxel.
// Positions are texture coordinates of the volume ([0, 1]^3); distances in the same units.
#ifndef BOUNCE_VCT_CONE_GLSL
#define BOUNCE_VCT_CONE_GLSL
#include "techniques/vct/sh.glsl"

layout(binding = BINDING_TEX_VCT_ALPHA) uniform sampler3D s_alpha;
layout(binding = BINDING_TEX_VCT_VOLUME0) uniform sampler3D s_vol[12];

// World position -> volume texture coordinates.
vec3 toTexture(vec3 world) { return (u_vct.voxelFromWorld * vec4(world, 1.0)).xyz * u_vct.grid.y; }

vec4 voxelFetch(vec3 pos, float lod, vec3 dir) {
    float range = u_vct.range.x;
#if VCT_STORAGE == VCT_STORAGE_ISO
    vec4 s = textureLod(s_alpha, pos, lod);
    return vec4(s.rgb * range, s.a);
#elif VCT_STORAGE == VCT_STORAGE_ANISO
    vec4 sX = dir.x < 0.0 ? textureLod(s_vol[1], pos, lod) : textureLod(s_vol[0], pos, lod);
    vec4 sY = dir.y < 0.0 ? textureLod(s_vol[3], pos, lod) : textureLod(s_vol[2], pos, lod);
    vec4 sZ = dir.z < 0.0 ? textureLod(s_vol[5], pos, lod) : textureLod(s_vol[4], pos, lod);
    vec3 w = dir * dir;
    vec4 s = w.x * sX + w.y * sY + w.z * sZ;
    return vec4(s.rgb * range, s.a);
#else
    vec4 b = shBasis(-normalize(dir));
#if VCT_STORAGE == VCT_STORAGE_SH_F32
    vec4 r = vec4(textureLod(s_vol[0], pos, lod).r, textureLod(s_vol[1], pos, lod).r, textureLod(s_vol[2], pos, lod).r, textureLod(s_vol[3], pos, lod).r);
    vec4 g = vec4(textureLod(s_vol[4], pos, lod).r, textureLod(s_vol[5], pos, lod).r, textureLod(s_vol[6], pos, lod).r, textureLod(s_vol[7], pos, lod).r);
    vec4 bl = vec4(textureLod(s_vol[8], pos, lod).r, textureLod(s_vol[9], pos, lod).r, textureLod(s_vol[10], pos, lod).r, textureLod(s_vol[11], pos, lod).r);
#else
    vec4 r = textureLod(s_vol[0], pos, lod) * u_vct.range.y;
    vec4 g = textureLod(s_vol[1], pos, lod) * u_vct.range.y;
    vec4 bl = textureLod(s_vol[2], pos, lod) * u_vct.range.y;
#endif
    // Eq. 5.9 averages over the active children: the SH radiance is that of the occupied part of the
    // voxel, so it is premultiplied by the voxel's opacity here (as the isotropic volume stores it).
    float alpha = textureLod(s_alpha, pos, lod).a;
    return vec4(max(vec3(dot(r, b), dot(g, b), dot(bl, b)), vec3(0.0)) * alpha, alpha);
#endif
}

// Returns (accumulated radiance, accessibility 1 - opacity at aoDist). nS: the surface normal used
// for the Eq. 6.1 start offset (fMin voxels along it); startAtOrigin skips that offset (diffuse and
// AO shift the origin along the normal instead, section 6.1.1).
vec4 coneTrace(vec3 origin, vec3 nS, vec3 dir, float coneRatio, float maxDist, float aoDist, float voxSize,
               float volDim, float fMin, float fMax, float sinHalfAngle, bool startAtOrigin) {
    vec4 accum = vec4(0.0);
    float opacity = 0.0;
    float startDist = 0.0;
    if (!startAtOrigin) {
        // Eq. 6.2 (as the spec reads the garbled conditions): d_s = clamp(f |v| / (n . w), fMin |v|, fMax |v|),
        // then back by the first sample's radius so that its centre sits at d_s.
        float NdotR = max(dot(nS, dir), 1e-4);
        float d0 = clamp(fMin * voxSize / NdotR, fMin * voxSize, fMax * voxSize);
        startDist = d0 - d0 * sinHalfAngle;
    }
    for (float dist = startDist; dist <= maxDist && accum.w < 1.0;) {
        float sampleRadius = coneRatio * dist;
        float sampleDiameter = max(2.0 * sampleRadius, voxSize);
        float sampleLod = log2(sampleDiameter * volDim);
        vec3 samplePos = origin + dir * (dist + sampleRadius);
        vec4 s = voxelFetch(samplePos, sampleLod, dir);
        float w = 1.0 - accum.w;
        accum += s * w;
        dist += sampleDiameter;
        opacity = dist < aoDist ? accum.w : opacity;
    }
    return vec4(accum.rgb, 1.0 - opacity);
}

vec4 coneTrace60(vec3 origin, vec3 dir, float maxDist, float aoDist, float voxSize) {
    vec4 accum = vec4(0.0);
    float opacity = 0.0;
    float sampleLod = 0.0;
    for (float dist = voxSize; dist <= maxDist && accum.w < 1.0;) {
        vec4 s = voxelFetch(origin + dir * dist, sampleLod, dir);
        float w = 1.0 - accum.w;
        accum.rgb += s.rgb * w;
        accum.w += s.w * w;
        sampleLod += 1.0;
        dist *= 2.0;
        opacity = dist < aoDist ? accum.w : opacity;
    }
    return vec4(accum.rgb, 1.0 - opacity);
}

#endif
