// The BRDF-frequency mipmap of Nichols 2010 §5.3.2.1 (checklist item 17: "while building the depth
// and normal mipmaps, also compute the cross-sectional Phong lobe size"): per cell of every level of
// the eye pyramid, the sharpest and broadest specular lobe under it, stored as GGX roughness, and how
// many specular and purely diffuse pixels it covers (a material boundary inside a cell refines it).
// The lobe width itself is computed from the minimum roughness where it is used (lobe.glsl).
// Texel: x min roughness of specular pixels (2 if none), y max roughness (-1 if none), z specular
// pixels, w diffuse-only covered pixels. Level 0 reads the G-buffer; level k reduces 2x2 children of
// level k-1 (3 on the last row/column of odd sizes, as pyramid_reduce.comp).
// Host uniforms: u_base, u_size, u_childSize. Inputs: G-buffer (u_base) or image BINDING_IMG0.
// Output: image BINDING_IMG1 (rgba32f 2D array, the level's mip).
#include "common/gbuffer.glsl"
layout(local_size_x = 8, local_size_y = 8) in;
layout(rgba32f, binding = BINDING_IMG0) readonly uniform image2DArray i_child;
layout(rgba32f, binding = BINDING_IMG1) writeonly uniform image2DArray i_level;
uniform bool u_base;
uniform ivec2 u_size;
uniform ivec2 u_childSize;

void main() {
    ivec2 t = ivec2(gl_GlobalInvocationID.xy);
    if (any(greaterThanEqual(t, u_size))) return;
    vec4 r = vec4(2.0, -1.0, 0.0, 0.0);
    if (u_base) {
        Surface s = readSurface(t);
        vec3 f0 = mix(vec3(s.specularF0), s.albedo, s.metallic);
        if (s.covered && max(f0.r, max(f0.g, f0.b)) > 0.0) r = vec4(s.roughness, s.roughness, 1.0, 0.0);
        else if (s.covered) r.w = 1.0;
    } else {
        ivec2 first = 2 * t;
        ivec2 last = mix(first + 1, u_childSize - 1, equal(t, u_size - 1));
        for (int y = first.y; y <= last.y; ++y)
            for (int x = first.x; x <= last.x; ++x) {
                vec4 c = imageLoad(i_child, ivec3(x, y, 0));
                r = vec4(min(r.x, c.x), max(r.y, c.y), r.z + c.z, r.w + c.w);
            }
    }
    imageStore(i_level, ivec3(t, 0), r);
}
