// Direct lighting of the camera G-buffer by one light (additively blended, one pass per light):
// common/direct.glsl's unshadowed radiance times the light's shadow-map visibility.
// Inputs: G-buffer, u_frame, u_light + shadow map. Output: radiance W/(m^2 sr), RGBA32F.
#include "common/frame.glsl"
#include "common/direct.glsl"

layout(location = 0) out vec4 o_radiance;

void main() {
    ivec2 pixel = ivec2(gl_FragCoord.xy);
    Surface s = readSurface(pixel);
    if (!s.covered) discard;
    vec3 radiance = unshadowedDirectRadiance(u_light, s, u_frame.eyePosition.xyz);
    if (max(radiance.r, max(radiance.g, radiance.b)) <= 0.0) discard;
    radiance *= shadowVisibility(u_light, s.position, s.normal);
    o_radiance = vec4(radiance, 1.0);
}
