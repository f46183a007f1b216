// Paraboloid shadow map depth. Triangles are straight in paraboloid space, so a vertex-interpolated
// position is not the surface point seen along this texel's direction (the paper tessellates the
// scene for this). Here the depth is exact inside each triangle: the texel's direction d(uv) (the
// inverse paraboloid map) is intersected with the triangle's plane, whose normal comes from the
// derivatives of the interpolated position (which stays on the plane). Only coverage at triangle
// edges keeps the straight-edge error. Inputs: v_local, u_far (metres), u_size (texels).
// Output: gl_FragDepth = distance / u_far. Alpha-masked texels occlude nothing (docs/scene.md).
#include "common/scene.glsl"
in vec3 v_local;
in vec2 v_uv;
flat in uint v_object;
uniform float u_far;
uniform vec2 u_size;

void main() {
    // Derivatives before any discard: after one they are undefined (issue 29 #4).
    vec3 n = cross(dFdx(v_local), dFdy(v_local));
    vec2 uv = gl_FragCoord.xy / u_size * 2.0 - 1.0;
    float r2 = dot(uv, uv);
    if (r2 > 1.0) discard;
    vec3 d = vec3(2.0 * uv, 1.0 - r2) / (1.0 + r2);
    float denom = dot(n, d);
    float t = length(v_local);
    // Edge-on triangles (denominator ~0 relative to |n|) keep the interpolated distance.
    if (abs(denom) > 1e-6 * length(n)) t = dot(n, v_local) / denom;
    if (!(t > 0.0)) discard;
    // Last, after every derivative: textureLod needs none.
    if (materialMasked(u_objects[v_object].info.x, v_uv)) discard;
    gl_FragDepth = clamp(t / u_far, 0.0, 1.0);
}
