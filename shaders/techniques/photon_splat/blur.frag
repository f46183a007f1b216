// Photon splatting (seed 004, §3.5/§4.4): one direction of the optional separable Gaussian blur of
// the indirect light, kernel 3, 5, 7 or 9 pixels (sigma = kernel / 4: not given by the document).
layout(binding = BINDING_TEX_INPUT0) uniform sampler2D s_input;
uniform ivec2 u_direction;
uniform int u_kernel;
layout(location = 0) out vec4 o_radiance;
void main() {
    ivec2 p = ivec2(gl_FragCoord.xy);
    ivec2 size = textureSize(s_input, 0);
    int r = u_kernel / 2;
    float sigma = float(u_kernel) / 4.0;
    vec3 sum = vec3(0.0);
    float wsum = 0.0;
    for (int i = -r; i <= r; ++i) {
        ivec2 q = clamp(p + i * u_direction, ivec2(0), size - 1);
        float w = exp(-0.5 * float(i * i) / (sigma * sigma));
        sum += w * texelFetch(s_input, q, 0).rgb;
        wsum += w;
    }
    o_radiance = vec4(sum / wsum, 1.0);
}
