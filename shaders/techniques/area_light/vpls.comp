// VPLs on a textured area light (Nichols 2010 §5.3.2.1, checklist item 15): a regular n x n grid
// (thesis 16 x 16 = 256) over the rectangle; VPL (a, b) sits at its cell's centre, carries the cell's
// area A / n^2 and the light texture's average over the cell, read from the mip level whose texels
// are one cell wide (the texture is mip-mapped so it "can be sampled by lobe footprint"); an
// assumption the summary marks as inference: A(y_i) = A / 256, I(y_i) = the prefiltered block.
// Host uniforms: u_light (index into u_pass.lights). Inputs: the light's texture (BINDING_TEX_AREA_LIGHT).
// Output: AreaVplGpu[] (BINDING_SSBO_TECH0) from index u_pass.lights[u_light].texture.z.
#include "techniques/area_light/area_common.glsl"
layout(local_size_x = 64) in;
layout(binding = BINDING_TEX_AREA_LIGHT) uniform sampler2D s_texture;
layout(std430, binding = BINDING_SSBO_TECH0) writeonly buffer VplBlock { AreaVplGpu u_vpls[]; };
uniform int u_light;

void main() {
    AreaLightGpu L = u_pass.lights[u_light];
    int n = int(L.texture.w);
    int i = int(gl_GlobalInvocationID.x);
    if (i >= n * n) return;
    vec2 uv = (vec2(i % n, i / n) + 0.5) / float(n);
    vec3 p = L.centre.xyz + (uv.x - 0.5) * L.edgeU.xyz + (uv.y - 0.5) * L.edgeV.xyz;
    vec3 radiance = L.radiance.rgb;
    if (L.radiance.w > 0.5) {
        float lod = log2(max(L.texture.x / float(n), L.texture.y / float(n)));
        radiance *= textureLod(s_texture, uv, max(lod, 0.0)).rgb;
    }
    u_vpls[int(L.texture.z) + i] = AreaVplGpu(vec4(p, float(u_light)), vec4(radiance, L.normal.w / float(n * n)));
}
