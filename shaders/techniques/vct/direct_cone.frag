// Rauwendaal 2013 section 6.2, Eq. 6.3: soft shadows by one cone per pixel towards the light,
// S = 1 - prod_i (1 - alpha_i) accumulated front to back by the generic tracer (Fig. B.4); the
// visibility 1 - S multiplies the unshadowed direct radiance (common/direct.glsl), as Eq. 7.3 uses
// the voxel-traced shadow for the pixel's direct term. The cone starts at Eq. 6.2's distance from an
// origin moved f voxels along the normal (section 6.1.1), and ends one voxel before the light.
// Aperture u_vct.cone2.w (radians; 0 = a ray marched at LOD 0). One additive pass per light
// (u_light, BINDING_UBO_LIGHT). Output: direct radiance W/(m^2 sr), RGBA32F.
#include "common/constants.glsl"
#include "common/frame.glsl"
#include "common/direct.glsl"
#include "techniques/vct/volume.glsl"
#include "techniques/vct/cone.glsl"

layout(location = 0) out vec4 o_radiance;

void main() {
    Surface s = readSurface(ivec2(gl_FragCoord.xy));
    if (!s.covered) discard;
    vec3 radiance = unshadowedDirectRadiance(u_light, s, u_frame.eyePosition.xyz);
    if (max(radiance.r, max(radiance.g, radiance.b)) <= 0.0) discard;
    float N = u_vct.grid.x, voxSize = u_vct.grid.y;
    vec3 x = toTexture(s.position);
    vec3 origin = x + s.normal * (u_vct.cone.x * voxSize);
    vec3 dir;
    float dist;
    if (lightType(u_light) == LIGHT_DIRECTIONAL) {
        dir = -normalize(u_light.direction.xyz);
        dist = 2.0;  // across the whole unit cube
    } else {
        vec3 d = toTexture(u_light.position.xyz) - origin;
        dist = length(d) - voxSize;
        dir = d / max(length(d), 1e-9);
    }
    float sinHalf = sin(0.5 * u_vct.cone2.w);
    vec4 c = coneTrace(origin, s.normal, dir, sinHalf / (1.0 - sinHalf), dist, 2.0 * dist + 1.0, voxSize, N,
                       u_vct.cone.x, u_vct.cone.y, sinHalf, false, u_vct.cone.x * voxSize, dot(dir, s.normal));
    o_radiance = vec4(radiance * c.a, 1.0);
}
