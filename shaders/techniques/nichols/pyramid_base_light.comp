// Base level of the light-space min-max pyramid over the RSM (Nichols 2010 §4.2.2, checklist item 13):
// position, normal, flux and area per texel, the relative light-distance derivative (as the eye-space
// one, Fig. 4.2(c)) and the light distance ||V_j|| (max-reduced for Eq. 4.8's conservative bound).
// Inputs: RSM arrays (BINDING_TEX_TECH0..2). Outputs: pyramid level 0, images BINDING_IMG0..4.
#include "techniques/nichols/pyramid.glsl"
layout(local_size_x = 8, local_size_y = 8) in;
layout(binding = BINDING_TEX_TECH0) uniform sampler2DArray s_rsmPosition;
layout(binding = BINDING_TEX_TECH1) uniform sampler2DArray s_rsmNormal;
layout(binding = BINDING_TEX_TECH2) uniform sampler2DArray s_rsmFlux;
layout(rgba32f, binding = BINDING_IMG0) writeonly uniform image2DArray i_geometry;
layout(rgba32f, binding = BINDING_IMG1) writeonly uniform image2DArray i_normal;
layout(rgba32f, binding = BINDING_IMG2) writeonly uniform image2DArray i_normalMin;
layout(rgba32f, binding = BINDING_IMG3) writeonly uniform image2DArray i_normalMax;
layout(rgba32f, binding = BINDING_IMG4) writeonly uniform image2DArray i_flux;
uniform ivec2 u_size;

float lightDistance(ivec3 t, out bool covered) {
    vec4 x = texelFetch(s_rsmPosition, t, 0);
    covered = texelFetch(s_rsmFlux, t, 0).a > 0.5;
    return x.w;
}

float axisDerivative(ivec3 t, ivec2 step, float d0) {
    ivec2 a = t.xy + step, b = t.xy - step;
    bool inA = all(lessThan(a, u_size)), inB = all(greaterThanEqual(b, ivec2(0)));
    float d = 0.0;
    bool c;
    if (inA) {
        float da = lightDistance(ivec3(a, t.z), c);
        if (!c) return kDerivativeOfEdge;
        d = max(d, abs(da - d0));
    }
    if (inB) {
        float db = lightDistance(ivec3(b, t.z), c);
        if (!c) return kDerivativeOfEdge;
        d = max(d, abs(d0 - db));
    }
    return d;
}

void main() {
    ivec3 t = ivec3(gl_GlobalInvocationID.xyz);
    if (any(greaterThanEqual(t.xy, u_size))) return;
    bool covered;
    float d0 = lightDistance(t, covered);
    if (!covered) {
        imageStore(i_geometry, t, vec4(0.0));
        imageStore(i_normal, t, vec4(0.0));
        imageStore(i_normalMin, t, vec4(vec3(kNormalEmptyMin), 1.0));
        imageStore(i_normalMax, t, vec4(vec3(kNormalEmptyMax), 0.0));
        imageStore(i_flux, t, vec4(0.0));
        return;
    }
    vec4 n = texelFetch(s_rsmNormal, t, 0);
    float dx = axisDerivative(t, ivec2(1, 0), d0), dy = axisDerivative(t, ivec2(0, 1), d0);
    float derivative = dx >= kDerivativeOfEdge || dy >= kDerivativeOfEdge ? kDerivativeOfEdge : sqrt(dx * dx + dy * dy) / max(d0, 1e-6);
    imageStore(i_geometry, t, vec4(texelFetch(s_rsmPosition, t, 0).xyz, 1.0));
    imageStore(i_normal, t, vec4(n.xyz, derivative));
    imageStore(i_normalMin, t, vec4(n.xyz, 0.0));
    imageStore(i_normalMax, t, vec4(n.xyz, d0));
    imageStore(i_flux, t, vec4(texelFetch(s_rsmFlux, t, 0).rgb, n.w));
}
