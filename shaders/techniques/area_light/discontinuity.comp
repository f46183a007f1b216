// Illumination discontinuities of level k (Nichols 2010 §5.3.4: "rapid color changes between coarse
// samples" against a user colour threshold, 0.005 in Fig. 5.10), after level k was gathered and
// upsampled: a rendered cell whose 3x3 neighbourhood in the upsampled result varies, in some channel,
// by more than u_pass.refine.x is flagged for refinement, so that its children are rendered at level
// k - 1. The thesis compares display colours; bounce compares the radiance of a white receiver
// (irradiance / pi for the diffuse buffer; the specular buffer's radiance / F), in W/(m^2 sr): at
// bounce's default exposure (0 EV) 1 W/(m^2 sr) is about display white, so 0.005 is the thesis's half
// percent of the display range (assumption: the exposure the thesis's colours had is not given).
// Relative to the lights' emitted radiance (the earlier normalization) 0.005 was 0.2 W/(m^2 sr) on
// cornell-box-area, whose light is 40 times brighter than its brightest receiver: no cell refined.
// Host uniforms: u_level, u_levelOrigin, u_size, u_scale (1 / pi diffuse, 1 specular).
// Inputs: upsampled result (BINDING_TEX_TECH0, 2D array, lod = level). In/out: flags (image BINDING_IMG1).
#include "techniques/area_light/area_shared.h"
layout(std140, binding = BINDING_UBO_PASS) uniform AreaPassBlock { AreaPassUniforms u_pass; };
layout(local_size_x = 8, local_size_y = 8) in;
layout(binding = BINDING_TEX_TECH0) uniform sampler2DArray s_result;
layout(r32ui, binding = BINDING_IMG1) uniform uimage2D i_flags;
uniform int u_level;
uniform ivec2 u_levelOrigin;
uniform ivec2 u_size;
uniform float u_scale;

void main() {
    ivec2 c = ivec2(gl_GlobalInvocationID.xy);
    if (any(greaterThanEqual(c, u_size))) return;
    uint flags = imageLoad(i_flags, u_levelOrigin + c).r;
    if ((flags & AL_CELL_RENDERED) == 0u) return;
    vec3 lo = vec3(1e30), hi = vec3(-1e30);
    for (int dy = -1; dy <= 1; ++dy)
        for (int dx = -1; dx <= 1; ++dx) {
            ivec2 q = c + ivec2(dx, dy);
            if (any(lessThan(q, ivec2(0))) || any(greaterThanEqual(q, u_size))) continue;
            vec4 r = texelFetch(s_result, ivec3(q, 0), u_level);
            if (r.a < 0.5) continue;
            lo = min(lo, r.rgb);
            hi = max(hi, r.rgb);
        }
    vec3 range = (hi - lo) * u_scale;
    if (max(range.r, max(range.g, range.b)) > u_pass.refine.x)
        imageStore(i_flags, u_levelOrigin + c, uvec4(flags | AL_CELL_REFINE));
}
