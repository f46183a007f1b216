// Rauwendaal 2013 ch. 6: voxel cone tracing over the mipmapped volumes.
//   voxelFetch (section 5.2, Figs. B.2-B.3): isotropic fetch; the ambient cube of the six anisotropic
//     faces weighted by the squared cone direction (opacity blended as transmittance, u_vct.trace.w); 2-band SH evaluated at -dir (clamped at 0: the
//     thesis clamps to [0, 1] for its LDR colours, radiance here is HDR). Every format stores colour
//     premultiplied by opacity (the SH coefficients too), so textureLod's filtering across occupied and
//     empty voxels is the filter of premultiplied values that Fig. B.4's compositing needs. Quadrilinear:
//     textureLod with a fractional level. Returns (premultiplied radiance W/(m^2 sr), opacity).
//   coneTrace (Fig. B.4): the generic tracer, cone ratio sin(theta/2) / (1 - sin(theta/2)), sample
//     diameter >= one voxel, LOD = log2(diameter N), front-to-back accumulation, exit at opacity 1 or
//     maxDist, AO frozen at aoDist; with the tangent cap (below).
//   coneTrace60 (Fig. B.5): the specialised 60-degree diffuse tracer sampling at integer LODs,
//     distance doubling from one voxel (as printed: no tangent cap, which its fixed doubling cannot
//     follow without leaving gaps).
// Tangent cap (u_vct.trace.x, bounce's fix, docs/techniques/vct.md "Where the light goes"): a
// generic-tracer sample whose trilinear footprint would reach below the receiver's tangent plane
// takes the finest level whose footprint stays above it (and steps by that level's texel), so a
// receiver no longer lights or occludes itself through the filter (a lone lit plane received
// indirect light of up to 0.66 of its direct light). Opacity correction (u_vct.trace.y, iso and
// SH only): see correctedSample. Cones end where they leave the grid (nothing lies outside it).
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
    vec4 s = w.x * sX + w.y * sY + w.z * sZ;  // Fig. B.2's ambient cube
    if (u_vct.trace.w > 0.5 && s.a > 0.0) {
        // Transmittance blend (bounce's choice): 1 - prod (1 - a_i)^w_i instead of the linear sum of
        // the faces' opacities. A plane opaque along its normal axis (a_x = 1) stops every ray that is
        // not parallel to it; the linear blend let a ray at 45 degrees through half of it. Colour keeps
        // Fig. B.2's weights, rescaled to the blended opacity (premultiplied).
        float a = 1.0 - pow(1.0 - sX.a, w.x) * pow(1.0 - sY.a, w.y) * pow(1.0 - sZ.a, w.z);
        s = vec4(s.rgb * (a / s.a), a);
    }
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
    // The SH mip (passes.glsl) stores coefficients premultiplied by opacity, as the isotropic volume.
    float alpha = textureLod(s_alpha, pos, lod).a;
    return vec4(max(vec3(dot(r, b), dot(g, b), dot(bl, b)), vec3(0.0)), alpha);
#endif
}

// Opacity correction for the step length (volume-rendering practice: Engel et al., Real-Time Volume
// Graphics, 2006, ch. 9.1; the alpha correction of Crassin et al. 2011). An iso or SH voxel holds the
// mean opacity of its level-0 voxels (5.3.1), i.e. an opacity per level-0 voxel of path; a sample that
// stands for `steps` level-0 voxels of path has opacity 1 - (1 - a)^steps. Without it a one-voxel wall
// seen at level k has opacity 2^-k and a cone crossing it keeps 1 - 2^-k of what lies behind
// (docs/techniques/vct.md, "Where the light goes"). Anisotropic faces already composite their
// children along the direction (5.3.2) and are left as they are.
vec4 correctedSample(vec4 s, float steps) {
#if VCT_STORAGE != VCT_STORAGE_ANISO
    if (u_vct.trace.y > 0.5 && s.a > 0.0 && s.a < 1.0) {
        float a = 1.0 - pow(1.0 - s.a, steps);
        s = vec4(s.rgb * (a / s.a), a);
    }
#endif
    return s;
}

// Returns (accumulated radiance, accessibility 1 - opacity at aoDist). nS: the surface normal used
// for the Eq. 6.1 start offset (fMin voxels along it); startAtOrigin skips that offset (diffuse and
// AO shift the origin along the normal instead, section 6.1.1).
bool insideGrid(vec3 p) { return all(greaterThanEqual(p, vec3(0.0))) && all(lessThanEqual(p, vec3(1.0))); }

// The tangent cap: lowers `lod` (and the sample's diameter and radius with it) until the trilinear
// footprint of a sample at `dist` (near edge) stays above the receiver's tangent plane, `h0` above the
// cone's origin and rising by `rise` per unit of distance along the cone. A texel of size t holding the
// plane has its centre at most t/2 above it and weighs 0 at a sample 1.5 t or more above the plane;
// the sample's height depends on its radius, hence the few iterations (the height only falls). Returns
// false for a sample less than 1.5 level-0 voxels above the plane, which could only see the receiver's
// own voxels (a grazing specular cone's first steps): the caller skips it.
bool tangentCap(float dist, float h0, float rise, float voxSize, float volDim, inout float lod, inout float diameter,
                inout float radius) {
    if (u_vct.trace.x < 0.5) return true;
    for (int it = 0; it < 4; ++it) {
        float h = (h0 + rise * (dist + radius)) * volDim;  // voxels above the tangent plane
        if (h < 1.5) return false;
        float capLod = floor(log2(h / 1.5));
        if (lod <= capLod) return true;
        lod = capLod;
        diameter = exp2(capLod) * voxSize;
        radius = 0.5 * diameter;
    }
    return true;
}

vec4 coneTrace(vec3 origin, vec3 nS, vec3 dir, float coneRatio, float maxDist, float aoDist, float voxSize,
               float volDim, float fMin, float fMax, float sinHalfAngle, bool startAtOrigin, float h0, float rise) {
    vec4 accum = vec4(0.0);
    float opacity = 0.0;
    float startDist = 0.0;
    if (!startAtOrigin) {
        // Eq. 6.2 (as the spec reads the garbled conditions): d_s = clamp(f |v| / (n . w), fMin |v|, fMax |v|),
        // |v| the voxel diagonal (26-separating) or side (6-separating), u_vct.trace.z voxels; then back
        // by the first sample's radius so that its centre sits at d_s.
        float NdotR = max(dot(nS, dir), 1e-4);
        float extent = u_vct.trace.z * voxSize;
        float d0 = clamp(fMin * extent / NdotR, fMin * extent, fMax * extent);
        startDist = d0 - d0 * sinHalfAngle;
    }
    for (float dist = startDist; dist <= maxDist && accum.w < 1.0 && insideGrid(origin + dir * dist);) {
        float sampleRadius = coneRatio * dist;
        float sampleDiameter = max(2.0 * sampleRadius, voxSize);
        float sampleLod = log2(sampleDiameter * volDim);
        if (!tangentCap(dist, h0, rise, voxSize, volDim, sampleLod, sampleDiameter, sampleRadius)) {
            dist += voxSize;
            continue;
        }
        vec3 samplePos = origin + dir * (dist + sampleRadius);
        vec4 s = correctedSample(voxelFetch(samplePos, sampleLod, dir), sampleDiameter * volDim);
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
    // The sample at distance d stands for the path to the next one, at 2d: d / voxSize level-0 voxels.
    for (float dist = voxSize; dist <= maxDist && accum.w < 1.0 && insideGrid(origin + dir * dist);) {
        vec4 s = correctedSample(voxelFetch(origin + dir * dist, sampleLod, dir), dist / voxSize);
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
