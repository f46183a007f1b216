// Refinement flags of one pyramid level (Nichols 2010 §3.2.3 / §3.4.2 / §4.2.1.1). A cell has a
// discontinuity when it mixes covered and uncovered texels, its max relative depth derivative exceeds
// u_depthThreshold, a normal component's max - min exceeds u_normalThreshold (range 0..2), or, with
// u_curvature (eye pyramid, §3.3.1), its max curvature (Eq. 3.1) exceeds u_curvatureThreshold. With
// u_linearDepth (eye pyramid, §3.2.2.1's conventional min-max mipmap) the depth test is instead
// (max - min) / min of the cell's view depths > u_depthThreshold. The
// test covers the cell and its four diagonal neighbours (§3.4.2; u_edgeNeighbours adds the four edge
// neighbours). refine(k) = discontinuity(k) OR refine of any child (k >= 2): refinement is monotone up
// the pyramid, which makes "valid at level k" = !refine(k) AND refine(k+1) select exactly one level
// per covered pixel.
// Inputs: level k (images 0..3), refine of level k-1 (image 4), curvature of level k (image 6, if u_curvature).
// Output: refine of level k (image 5, r32f).
#include "techniques/nichols/pyramid.glsl"
layout(local_size_x = 8, local_size_y = 8) in;
layout(rgba32f, binding = BINDING_IMG0) readonly uniform image2DArray i_geometry;
layout(rgba32f, binding = BINDING_IMG1) readonly uniform image2DArray i_normal;
layout(rgba32f, binding = BINDING_IMG2) readonly uniform image2DArray i_normalMin;
layout(rgba32f, binding = BINDING_IMG3) readonly uniform image2DArray i_normalMax;
layout(r32f, binding = BINDING_IMG4) readonly uniform image2DArray i_childRefine;
layout(r32f, binding = BINDING_IMG5) writeonly uniform image2DArray i_refine;
layout(rgba32f, binding = BINDING_IMG6) readonly uniform image2DArray i_curvature;
uniform ivec2 u_size;
uniform ivec2 u_childSize;
uniform bool u_childHasFlags;
uniform float u_depthThreshold;
uniform float u_normalThreshold;
uniform bool u_edgeNeighbours;
uniform bool u_curvature;
uniform float u_curvatureThreshold;
uniform bool u_linearDepth;

bool discontinuity(ivec3 t) {
    if (any(lessThan(t.xy, ivec2(0))) || any(greaterThanEqual(t.xy, u_size))) return false;
    float covered = imageLoad(i_geometry, t).w;
    vec4 nMin = imageLoad(i_normalMin, t), nMax = imageLoad(i_normalMax, t);
    if (covered > 0.0 && nMin.w > 0.0) return true;
    if (covered == 0.0) return false;
    if (u_linearDepth) {
        float zMin = imageLoad(i_normal, t).w;
        if (nMax.w - zMin > u_depthThreshold * max(zMin, 1e-6)) return true;
    } else if (imageLoad(i_normal, t).w > u_depthThreshold) {
        return true;
    }
    if (u_curvature && imageLoad(i_curvature, t).r > u_curvatureThreshold) return true;
    return any(greaterThan(nMax.xyz - nMin.xyz, vec3(u_normalThreshold)));
}

void main() {
    ivec3 t = ivec3(gl_GlobalInvocationID.xyz);
    if (any(greaterThanEqual(t.xy, u_size))) return;
    bool refine = discontinuity(t) || discontinuity(t + ivec3(1, 1, 0)) || discontinuity(t + ivec3(-1, 1, 0)) ||
                  discontinuity(t + ivec3(1, -1, 0)) || discontinuity(t + ivec3(-1, -1, 0));
    if (u_edgeNeighbours)
        refine = refine || discontinuity(t + ivec3(1, 0, 0)) || discontinuity(t + ivec3(-1, 0, 0)) ||
                 discontinuity(t + ivec3(0, 1, 0)) || discontinuity(t + ivec3(0, -1, 0));
    if (u_childHasFlags && !refine) {
        ivec2 first = 2 * t.xy;
        ivec2 last = mix(first + 1, u_childSize - 1, equal(t.xy, u_size - 1));
        for (int y = first.y; y <= last.y; ++y)
            for (int x = first.x; x <= last.x; ++x) refine = refine || imageLoad(i_childRefine, ivec3(x, y, t.z)).r > 0.5;
    }
    imageStore(i_refine, t, vec4(refine ? 1.0 : 0.0));
}
