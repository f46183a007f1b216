// The indirect-resolution cap (setting `indirectSize`, thesis ch. 3): level 0 of the upsampled
// multiresolution result is ceil(output / u_scale) texels, texel t standing for the output block
// [t * u_scale, (t + 1) * u_scale). An output pixel takes the bilinear interpolation of the four
// nearest result texels at its centre, counting only texels that have data (alpha 1): empty-aware
// bilinear, so light neither leaks from nor into uncovered blocks; where none of the four has data, the
// nearest texel (zero if it has none). u_scale = 1 reads the pixel's own texel (the full-size path).
// Host uniform: u_scale.
uniform int u_scale;

vec3 upsampledIrradiance(sampler2DArray result, ivec2 pixel) {
    if (u_scale == 1) return texelFetch(result, ivec3(pixel, 0), 0).rgb;
    ivec2 size = textureSize(result, 0).xy;
    vec2 t = (vec2(pixel) + 0.5) / float(u_scale) - 0.5;
    ivec2 t0 = ivec2(floor(t));
    vec2 f = t - vec2(t0);
    vec3 sum = vec3(0.0);
    float weight = 0.0;
    for (int dy = 0; dy <= 1; ++dy)
        for (int dx = 0; dx <= 1; ++dx) {
            ivec2 q = clamp(t0 + ivec2(dx, dy), ivec2(0), size - 1);
            vec4 v = texelFetch(result, ivec3(q, 0), 0);
            float w = (dx == 1 ? f.x : 1.0 - f.x) * (dy == 1 ? f.y : 1.0 - f.y);
            if (v.a > 0.5 && w > 0.0) {
                sum += w * v.rgb;
                weight += w;
            }
        }
    if (weight > 0.0) return sum / weight;
    vec4 nearest = texelFetch(result, ivec3(min(pixel / u_scale, size - 1), 0), 0);
    return nearest.a > 0.5 ? nearest.rgb : vec3(0.0);
}
