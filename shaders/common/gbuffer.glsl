// Reading the camera G-buffer (render/gbuffer.frag wrote it; see that file for the encoding).
layout(binding = BINDING_TEX_GBUF_POSITION) uniform sampler2D s_gPosition;
layout(binding = BINDING_TEX_GBUF_NORMAL) uniform sampler2D s_gNormal;
layout(binding = BINDING_TEX_GBUF_ALBEDO) uniform sampler2D s_gAlbedo;
layout(binding = BINDING_TEX_GBUF_EMISSION) uniform sampler2D s_gEmission;

struct Surface {
    bool covered;
    vec3 position;
    vec3 normal;
    vec3 albedo;
    vec3 emission;
    float roughness, metallic, specularF0;
};

Surface readSurface(ivec2 pixel) {
    vec4 p = texelFetch(s_gPosition, pixel, 0);
    vec4 n = texelFetch(s_gNormal, pixel, 0);
    vec4 a = texelFetch(s_gAlbedo, pixel, 0);
    vec4 e = texelFetch(s_gEmission, pixel, 0);
    Surface s;
    s.covered = p.w > 0.5;
    s.position = p.xyz;
    s.normal = normalize(n.xyz + vec3(0.0, 0.0, 1e-12));
    s.roughness = n.w;
    s.albedo = a.rgb;
    s.metallic = a.w;
    s.emission = e.rgb;
    s.specularF0 = e.w;
    return s;
}
