// One level of the min-max pyramid (Nichols 2010 §3.2.2): each texel combines its 2x2 children (3 on
// the last row/column of odd-sized levels): sums of position, normal, flux and area; max of the depth
// derivative and of the depth; per-component min/max of the normal; covered/uncovered counts; the
// fifth chain is the light pyramid's flux (summed) or the eye pyramid's optional curvature (max only,
// §3.3.1). With u_linearDepth (eye pyramid, §3.2.2.1) normal.w is the min of the children's view depths.
// Host uniforms: u_childLevel (k-1), u_childSize, u_size, u_hasFlux (light pyramid), u_hasCurvature (eye
// pyramid), u_linearDepth.
// Inputs: level k-1 through texelFetch on the same textures (units BINDING_TEX_PYRAMID0..4): five images
// plus five outputs would be 10 image units, past GL 4.5's and NVIDIA's 8 (issue 29 finding #1).
// Outputs: level k (images BINDING_IMG0..4). Reading level k-1 by a sampler while level k is written as an
// image is defined: different levels, and the previous dispatch ends in GL_TEXTURE_FETCH_BARRIER_BIT.
#include "techniques/nichols/pyramid.glsl"
layout(local_size_x = 8, local_size_y = 8) in;
layout(binding = BINDING_TEX_PYRAMID0) uniform sampler2DArray s_geometryIn;
layout(binding = BINDING_TEX_PYRAMID1) uniform sampler2DArray s_normalIn;
layout(binding = BINDING_TEX_PYRAMID2) uniform sampler2DArray s_normalMinIn;
layout(binding = BINDING_TEX_PYRAMID3) uniform sampler2DArray s_normalMaxIn;
layout(binding = BINDING_TEX_PYRAMID4) uniform sampler2DArray s_fluxIn;
layout(rgba32f, binding = BINDING_IMG0) writeonly uniform image2DArray i_geometryOut;
layout(rgba32f, binding = BINDING_IMG1) writeonly uniform image2DArray i_normalOut;
layout(rgba32f, binding = BINDING_IMG2) writeonly uniform image2DArray i_normalMinOut;
layout(rgba32f, binding = BINDING_IMG3) writeonly uniform image2DArray i_normalMaxOut;
layout(rgba32f, binding = BINDING_IMG4) writeonly uniform image2DArray i_fluxOut;
uniform int u_childLevel;
uniform ivec2 u_childSize;
uniform ivec2 u_size;
uniform bool u_hasFlux;
uniform bool u_hasCurvature;
uniform bool u_linearDepth;

void main() {
    ivec3 t = ivec3(gl_GlobalInvocationID.xyz);
    if (any(greaterThanEqual(t.xy, u_size))) return;
    ivec2 first = 2 * t.xy;
    ivec2 last = mix(first + 1, u_childSize - 1, equal(t.xy, u_size - 1));
    vec4 g = vec4(0.0), n = vec4(0.0), nMin = vec4(vec3(kNormalEmptyMin), 0.0), nMax = vec4(vec3(kNormalEmptyMax), 0.0),
         f = vec4(0.0);
    if (u_linearDepth) n.w = kDepthOfEmpty;
    for (int y = first.y; y <= last.y; ++y)
        for (int x = first.x; x <= last.x; ++x) {
            ivec3 c = ivec3(x, y, t.z);
            g += texelFetch(s_geometryIn, c, u_childLevel);
            vec4 cn = texelFetch(s_normalIn, c, u_childLevel);
            n.xyz += cn.xyz;
            n.w = u_linearDepth ? min(n.w, cn.w) : max(n.w, cn.w);
            vec4 cMin = texelFetch(s_normalMinIn, c, u_childLevel), cMax = texelFetch(s_normalMaxIn, c, u_childLevel);
            nMin.xyz = min(nMin.xyz, cMin.xyz);
            nMin.w += cMin.w;
            nMax.xyz = max(nMax.xyz, cMax.xyz);
            nMax.w = max(nMax.w, cMax.w);
            if (u_hasFlux) f += texelFetch(s_fluxIn, c, u_childLevel);
            if (u_hasCurvature) f.r = max(f.r, texelFetch(s_fluxIn, c, u_childLevel).r);
        }
    imageStore(i_geometryOut, t, g);
    imageStore(i_normalOut, t, n);
    imageStore(i_normalMinOut, t, nMin);
    imageStore(i_normalMaxOut, t, nMax);
    if (u_hasFlux || u_hasCurvature) imageStore(i_fluxOut, t, f);
}
