// Base level of the eye-space min-max pyramid (Nichols 2010 §3.2.2) from the camera G-buffer:
// position, normal, and the relative linear-depth derivative sqrt(dz/dx^2 + dz/dy^2) / z with the
// larger of the forward and backward differences (so a pixel on either side of a depth edge sees it).
// Optional (u_curvature, §3.3.1): Eq. 3.1's curvature kappa = 2 sin(arccos(N1.N2) / 2) between this pixel
// and each covered 4-neighbour, the max of the four (so pixels on both sides of a crease see it),
// computed as the chord |N1 - N2| of the unit normals, equal to 2 sin(theta / 2) and exact (0) for
// equal normals where arccos of a rounded dot product is not.
// Indirect-resolution cap (u_scale > 1, setting `indirectSize`): base texel p is the G-buffer pixel at
// the centre of its u_scale x u_scale block (a point sample, as a G-buffer rendered at the lower
// resolution would hold), and neighbours are the adjacent blocks' samples, so the derivative and the
// curvature are per base texel.
// Linear depth (u_linearDepth, §3.2.2.1's conventional min-max mipmap): normal.w holds the texel's own
// view depth (the min chain; kDepthOfEmpty where uncovered) instead of the derivative; normalMax.w is
// the max chain in both modes.
// Host uniforms: u_size, u_curvature, u_scale, u_gbufferSize, u_linearDepth. Inputs: G-buffer, u_frame.
// Outputs: pyramid level 0 (see pyramid.glsl), images BINDING_IMG0..3, curvature image BINDING_IMG4.
#include "common/gbuffer.glsl"
#include "common/frame.glsl"
#include "techniques/nichols/pyramid.glsl"
layout(local_size_x = 8, local_size_y = 8) in;
layout(rgba32f, binding = BINDING_IMG0) writeonly uniform image2DArray i_geometry;
layout(rgba32f, binding = BINDING_IMG1) writeonly uniform image2DArray i_normal;
layout(rgba32f, binding = BINDING_IMG2) writeonly uniform image2DArray i_normalMin;
layout(rgba32f, binding = BINDING_IMG3) writeonly uniform image2DArray i_normalMax;
layout(rgba32f, binding = BINDING_IMG4) writeonly uniform image2DArray i_curvature;
uniform ivec2 u_size;
uniform bool u_curvature;
uniform int u_scale;
uniform ivec2 u_gbufferSize;
uniform bool u_linearDepth;

// The G-buffer pixel that base texel p samples (its block's centre).
ivec2 gbufferPixel(ivec2 p) { return min(p * u_scale + u_scale / 2, u_gbufferSize - 1); }

float viewDepth(ivec2 p, out bool covered) {
    p = clamp(p, ivec2(0), u_size - 1);
    vec4 x = texelFetch(s_gPosition, gbufferPixel(p), 0);
    covered = x.w > 0.5;
    return -(u_frame.viewFromWorld * vec4(x.xyz, 1.0)).z;
}

float axisDerivative(ivec2 p, ivec2 step, float z) {
    bool a, b;
    float za = viewDepth(p + step, a), zb = viewDepth(p - step, b);
    bool inA = all(lessThan(p + step, u_size)), inB = all(greaterThanEqual(p - step, ivec2(0)));
    if ((inA && !a) || (inB && !b)) return kDerivativeOfEdge;
    float d = 0.0;
    if (inA) d = max(d, abs(za - z));
    if (inB) d = max(d, abs(z - zb));
    return d;
}

float curvature(ivec2 p, vec3 n) {
    const ivec2 kNeighbours[4] = ivec2[4](ivec2(1, 0), ivec2(-1, 0), ivec2(0, 1), ivec2(0, -1));
    float kappa = 0.0;
    for (int i = 0; i < 4; ++i) {
        ivec2 q = p + kNeighbours[i];
        if (any(lessThan(q, ivec2(0))) || any(greaterThanEqual(q, u_size))) continue;
        Surface s = readSurface(gbufferPixel(q));
        if (s.covered) kappa = max(kappa, length(n - s.normal));
    }
    return kappa;
}

void main() {
    ivec2 p = ivec2(gl_GlobalInvocationID.xy);
    if (any(greaterThanEqual(p, u_size))) return;
    Surface s = readSurface(gbufferPixel(p));
    ivec3 t = ivec3(p, 0);
    if (u_curvature) imageStore(i_curvature, t, vec4(s.covered ? curvature(p, s.normal) : 0.0, 0.0, 0.0, 0.0));
    if (!s.covered) {
        imageStore(i_geometry, t, vec4(0.0));
        imageStore(i_normal, t, vec4(0.0, 0.0, 0.0, u_linearDepth ? kDepthOfEmpty : 0.0));
        imageStore(i_normalMin, t, vec4(vec3(kNormalEmptyMin), 1.0));
        imageStore(i_normalMax, t, vec4(vec3(kNormalEmptyMax), 0.0));
        return;
    }
    bool covered;
    float z = viewDepth(p, covered);
    float dx = axisDerivative(p, ivec2(1, 0), z), dy = axisDerivative(p, ivec2(0, 1), z);
    float derivative = dx >= kDerivativeOfEdge || dy >= kDerivativeOfEdge ? kDerivativeOfEdge : sqrt(dx * dx + dy * dy) / max(z, 1e-6);
    imageStore(i_geometry, t, vec4(s.position, 1.0));
    imageStore(i_normal, t, vec4(s.normal, u_linearDepth ? z : derivative));
    imageStore(i_normalMin, t, vec4(s.normal, 0.0));
    imageStore(i_normalMax, t, vec4(s.normal, z));
}
