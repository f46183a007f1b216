// van de Hoef 2013: the compute passes around the hemicubes. Host define RAD_PASS:
//   0 PLACE     hemicube records at elements (gather, Alg. 4.1) or shooters (front / back, old / new)
//   1 QUADSTATS per quad: area-weighted unshot and shot power, for FINDSHOOTINGQUAD (Alg. 4.2)
//   2 SHOOTERS  GENERATESHOOTINGPATCHES: the intermediate texture T (area-weighted sums per patch)
//   3 CLEAR     clear the unshot radiosity of the shooters' elements (Alg. 4.2 line 4), or reset
//               elements to their emission (Alg. 4.3 line 4) or to zero (the removal of M, sec. 4.5.2)
//   4 INTEGRATE multiply a hemicube by the delta form factors and sum it (compute reduction,
//               sec. 4.2), optionally from a mip chain's 1x1 level (the DX10 fallback); then
//               B_e = E_e + rho_e sum (gather) or B_s += rho_s sum (GATHERRADIOSITY, Alg. 4.4)
//   5 RESOLVE   average the samples of a multisampled hemicube array (colour and distance)
//   6 FFMUL     the mip fallback's first step: hemicube x delta form factors into mip level 0
//   7 LIGHTS    the direct light of point, spot and directional lights at the elements (D_new), and
//               its change shot into the solution: B += D_new - D, Bu += D_new - D, D = D_new
//               (bounce's extension: the thesis's only sources are emitting patches)
// Element radiosity lives in the atlas images: img0 B (total), img1 Bu (unshot), rgba32f; the
// punctual lights' direct radiance in img2 D_new (this frame's) and img3 D (what B holds of it).
#include "techniques/radiosity/patch.glsl"
#include "techniques/radiosity/hemicube.glsl"

layout(std430, binding = BINDING_SSBO_RAD_ELEMENTS) buffer RadElementBlock { RadElementGpu u_elements[]; };
layout(std430, binding = BINDING_SSBO_RAD_SHOOTERS) buffer RadShooterBlock { RadShooterGpu u_shooters[]; };
layout(std430, binding = BINDING_SSBO_RAD_STATS) buffer RadStatsBlock { vec4 u_stats[]; };
layout(binding = BINDING_IMG0, rgba32f) uniform coherent image2D i_total;
layout(binding = BINDING_IMG1, rgba32f) uniform coherent image2D i_unshot;

uniform int u_mode;
uniform uint u_first;   // first source item (element, shooter, quad, hemicube record)
uniform uint u_count;
uniform uint u_recordBase;
uniform int u_old;      // 1: place with the old bodies

ivec2 texelOf(RadElementGpu e) { return ivec2(e.info.y & 0xFFFFu, e.info.y >> 16); }

// 1x1 when the scene has no point, spot or directional light: loads outside an image return 0.
#if RAD_PASS == 3 || RAD_PASS == 7
layout(binding = BINDING_IMG2, rgba32f) uniform coherent image2D i_lightNew;
#endif
#if RAD_PASS == 3 || RAD_PASS == 4 || RAD_PASS == 7
layout(binding = BINDING_IMG3, rgba32f) uniform coherent image2D i_light;
#endif

#if RAD_PASS == 0 || RAD_PASS == 1 || RAD_PASS == 3 || RAD_PASS == 5 || RAD_PASS == 7
layout(local_size_x = 64) in;
#else
layout(local_size_x = 256) in;
#endif
// After the local size: dispatch.glsl reads gl_WorkGroupSize.
#include "common/dispatch.glsl"

#if RAD_PASS == 0
uniform float u_offset;   // metres off the surface
uniform float u_near;     // metres
uniform int u_rotate;     // random per-position rotation
void main() {
    uint k = linearInvocation();
    if (k >= u_count) return;
    bool old = u_old != 0;
    vec3 p, n;
    uint body, src = u_first + k;
    if (u_mode == 0) {  // at element src
        RadElementGpu e = u_elements[src];
        body = e.info.z;
        p = e.position.xyz;
        n = u_quads[e.info.x].normal.xyz;
    } else {            // at shooter src, front (1) or back (2)
        RadShooterGpu s = u_shooters[src];
        body = s.info.y;
        p = s.position.xyz;
        n = s.normal.xyz;
    }
    vec3 pw = (radWorldFromObject(body, old) * vec4(p, 1.0)).xyz;
    vec3 nw = radNormalToWorld(body, old, n);
    if (u_mode == 2) nw = -nw;
    RadHemicubeGpu h;
    vec3 origin = pw + nw * u_offset;
    vec3 T, B;
    hcFrame(nw, u_rotate != 0 ? hcRotationAngle(pw) : 0.0, T, B);
    h.origin = vec4(origin, u_near);
    h.tangent = vec4(T, 0.0);
    h.bitangent = vec4(B, 0.0);
    h.normal = vec4(nw, 0.0);
    h.info = uvec4(src, old ? 1u : 0u, 0u, 0u);
    u_hemicubes[u_recordBase + k] = h;
}
#elif RAD_PASS == 1
shared vec4 s_sum[64][3];
void main() {
    // The grid's last row has groups past the quads; they sum nothing and store nothing (no return:
    // GLSL 4.5 disallows barrier() after one).
    bool live = linearGroup() < u_count;
    uint q = u_first + (live ? linearGroup() : 0u);
    RadQuadGpu quad = u_quads[q];
    uint n = live ? quad.atlas.z * quad.atlas.w : 0u;
    vec4 unshot = vec4(0.0), shot = vec4(0.0), total = vec4(0.0);
    for (uint i = gl_LocalInvocationID.x; i < n; i += 64u) {
        RadElementGpu e = u_elements[quad.info.y + i];
        vec3 b = imageLoad(i_total, texelOf(e)).rgb, bu = imageLoad(i_unshot, texelOf(e)).rgb;
        float a = e.position.w;
        unshot += vec4(a * bu, a);
        shot += vec4(a * (b - bu), 0.0);
        total += vec4(a * b, 0.0);
    }
    s_sum[gl_LocalInvocationID.x][0] = unshot;
    s_sum[gl_LocalInvocationID.x][1] = shot;
    s_sum[gl_LocalInvocationID.x][2] = total;
    barrier();
    for (uint stride = 32u; stride > 0u; stride >>= 1) {
        if (gl_LocalInvocationID.x < stride)
            for (int c = 0; c < 3; ++c) s_sum[gl_LocalInvocationID.x][c] += s_sum[gl_LocalInvocationID.x + stride][c];
        barrier();
    }
    if (live && gl_LocalInvocationID.x == 0u) {
        // [3q]: unshot power (sum A Bu) and area; [3q+1]: shot power; [3q+2]: total power.
        u_stats[3u * q] = s_sum[0][0];
        u_stats[3u * q + 1u] = s_sum[0][1];
        u_stats[3u * q + 2u] = s_sum[0][2];
    }
}
#elif RAD_PASS == 2
// u_mode 0: all of T; 1: unshot and total only (Alg. 4.4 line 13 keeps the old shot for the
// negative term of the cross projection).
shared vec4 s_sum[256][4];
void main() {
    uint si = u_first + gl_WorkGroupID.x;
    RadShooterGpu s = u_shooters[si];
    RadQuadGpu quad = u_quads[s.info.x];
    uint nu = quad.atlas.z;
    uint w = s.range.z - s.range.x + 1u, hgt = s.range.w - s.range.y + 1u;
    vec4 pos = vec4(0.0), unshot = vec4(0.0), shot = vec4(0.0), total = vec4(0.0);
    for (uint i = gl_LocalInvocationID.x; i < w * hgt; i += 256u) {
        uint ei = quad.info.y + (s.range.y + i / w) * nu + s.range.x + i % w;
        RadElementGpu e = u_elements[ei];
        vec3 b = imageLoad(i_total, texelOf(e)).rgb, bu = imageLoad(i_unshot, texelOf(e)).rgb;
        float a = e.position.w;
        pos += vec4(a * e.position.xyz, a);
        unshot += vec4(a * bu, 0.0);
        shot += vec4(a * (b - bu), 0.0);
        total += vec4(a * b, 0.0);
    }
    uint l = gl_LocalInvocationID.x;
    s_sum[l][0] = pos;
    s_sum[l][1] = unshot;
    s_sum[l][2] = shot;
    s_sum[l][3] = total;
    barrier();
    for (uint stride = 128u; stride > 0u; stride >>= 1) {
        if (l < stride)
            for (int c = 0; c < 4; ++c) s_sum[l][c] += s_sum[l + stride][c];
        barrier();
    }
    if (l == 0u) {
        float area = s_sum[0][0].w;
        float inv = area > 0.0 ? 1.0 / area : 0.0;
        vec2 mid = 0.5 * (s.rect.xy + s.rect.zw);
        u_shooters[si].position = vec4(area > 0.0 ? s_sum[0][0].xyz * inv : radPointAt(quad, mid), area);
        u_shooters[si].normal = vec4(quad.normal.xyz, 0.0);
        u_shooters[si].unshot = vec4(s_sum[0][1].rgb * inv, 0.0);
        u_shooters[si].total = vec4(s_sum[0][3].rgb * inv, 0.0);
        if (u_mode == 0) u_shooters[si].shot = vec4(s_sum[0][2].rgb * inv, 0.0);
    }
}
#elif RAD_PASS == 3
// u_mode 0: Bu = 0 over the elements of shooters [u_first, u_first + u_count) (one group each);
// 1: B = Bu = E + D_new, D = D_new on the receivers u_receivers; 2: B = Bu = D = 0 on them.
uniform int u_receivers;
void main() {
    if (u_mode == 0) {
        RadShooterGpu s = u_shooters[u_first + gl_WorkGroupID.x];
        RadQuadGpu quad = u_quads[s.info.x];
        uint w = s.range.z - s.range.x + 1u, hgt = s.range.w - s.range.y + 1u;
        for (uint i = gl_LocalInvocationID.x; i < w * hgt; i += 64u) {
            uint ei = quad.info.y + (s.range.y + i / w) * quad.atlas.z + s.range.x + i % w;
            imageStore(i_unshot, texelOf(u_elements[ei]), vec4(0.0));
        }
        return;
    }
    uint ei = linearInvocation();
    if (ei >= u_count) return;
    RadElementGpu e = u_elements[ei];
    bool moving = radBodyMoving(e.info.z);
    if ((u_receivers == RAD_RECEIVERS_STATIC && moving) || (u_receivers == RAD_RECEIVERS_MOVING && !moving)) return;
    vec4 d = u_mode == 1 ? vec4(imageLoad(i_lightNew, texelOf(e)).rgb, 0.0) : vec4(0.0);
    vec4 v = u_mode == 1 ? vec4(e.emission.rgb, 0.0) + d : vec4(0.0);
    imageStore(i_total, texelOf(e), v);
    imageStore(i_unshot, texelOf(e), v);
    imageStore(i_light, texelOf(e), d);
}
#elif RAD_PASS == 4
// RAD_SOURCE 0: multisampled RGBA16F array (resolve folded into the sum); 1: single-sampled; 2: the
// 1x1 level of a mip chain of (hemicube x delta form factor), times the pixel count.
#if RAD_SOURCE == 0
layout(binding = BINDING_TEX_TECH2) uniform sampler2DMSArray s_hemicube;
#else
layout(binding = BINDING_TEX_TECH2) uniform sampler2DArray s_hemicube;
#endif
layout(binding = BINDING_TEX_TECH3) uniform sampler2DArray s_deltaFF;
uniform int u_resolution;
uniform int u_samples;
uniform int u_topLevel;
// u_mode 0: B_e = E_e + D_e + rho_e sum, Bu_e = 0 at the record's element (gather); 1: B_s += rho_s sum
// at the record's shooter's single element (GATHERRADIOSITY).
shared vec3 s_acc[256];
void main() {
    uint slot = gl_WorkGroupID.x;
    int R = u_resolution;
    vec3 acc = vec3(0.0);
#if RAD_SOURCE == 2
    if (gl_LocalInvocationID.x < 5u)
        acc = texelFetch(s_hemicube, ivec3(0, 0, int(slot) * 5 + int(gl_LocalInvocationID.x)), u_topLevel).rgb * float(R * R);
#else
    int perFace = R * R;
    for (int i = int(gl_LocalInvocationID.x); i < 5 * perFace; i += 256) {
        int face = i / perFace, p = i % perFace;
        ivec2 xy = ivec2(p % R, p / R);
        if (face != 0 && xy.y >= R / 2) continue;
        ivec3 c = ivec3(xy, int(slot) * 5 + face);
#if RAD_SOURCE == 0
        vec3 v = vec3(0.0);
        for (int s = 0; s < u_samples; ++s) v += texelFetch(s_hemicube, c, s).rgb;
        v /= float(u_samples);
#else
        vec3 v = texelFetch(s_hemicube, c, 0).rgb;
#endif
        acc += v * texelFetch(s_deltaFF, ivec3(xy, face), 0).r;
    }
#endif
    s_acc[gl_LocalInvocationID.x] = acc;
    barrier();
    for (uint stride = 128u; stride > 0u; stride >>= 1) {
        if (gl_LocalInvocationID.x < stride) s_acc[gl_LocalInvocationID.x] += s_acc[gl_LocalInvocationID.x + stride];
        barrier();
    }
    if (gl_LocalInvocationID.x != 0u) return;
    vec3 sum = s_acc[0];
    uint record = u_recordBase + slot;
    uint ei;
    if (u_mode == 0) {
        ei = u_hemicubes[record].info.x;
    } else {
        RadShooterGpu s = u_shooters[u_hemicubes[record].info.x];
        ei = u_quads[s.info.x].info.y + s.range.y * u_quads[s.info.x].atlas.z + s.range.x;
    }
    RadElementGpu e = u_elements[ei];
    ivec2 t = texelOf(e);
    if (u_mode == 0) {
        imageStore(i_total, t, vec4(e.emission.rgb + imageLoad(i_light, t).rgb + e.albedo.rgb * sum, 0.0));
        imageStore(i_unshot, t, vec4(0.0));
    } else {
        imageStore(i_total, t, imageLoad(i_total, t) + vec4(e.albedo.rgb * sum, 0.0));
    }
}
#elif RAD_PASS == 5
layout(binding = BINDING_TEX_TECH2) uniform sampler2DMSArray s_hemicube;
layout(binding = BINDING_IMG2, rgba16f) uniform writeonly image2DArray i_resolved;
uniform int u_samples;
uniform int u_resolution;
void main() {
    uint R = uint(u_resolution);
    uint i = linearInvocation();
    if (i >= R * R * u_count) return;
    ivec3 c = ivec3(int(i % R), int((i / R) % R), int(i / (R * R)));
    vec4 v = vec4(0.0);
    for (int s = 0; s < u_samples; ++s) v += texelFetch(s_hemicube, c, s);
    imageStore(i_resolved, c, v / float(u_samples));
}
#elif RAD_PASS == 6
layout(binding = BINDING_TEX_TECH2) uniform sampler2DMSArray s_hemicube;
layout(binding = BINDING_TEX_TECH3) uniform sampler2DArray s_deltaFF;
layout(binding = BINDING_IMG2, rgba32f) uniform writeonly image2DArray i_weighted;
uniform int u_samples;
uniform int u_resolution;
void main() {
    uint R = uint(u_resolution);
    uint i = linearInvocation();
    if (i >= R * R * u_count) return;
    ivec3 c = ivec3(int(i % R), int((i / R) % R), int(i / (R * R)));
    vec4 v = vec4(0.0);
    for (int s = 0; s < u_samples; ++s) v += texelFetch(s_hemicube, c, s);
    float ff = texelFetch(s_deltaFF, ivec3(c.xy, c.z % 5), 0).r;
    imageStore(i_weighted, c, vec4(v.rgb / float(u_samples) * ff, 0.0));
}
#elif RAD_PASS == 7
#include "common/lighting.glsl"
// u_mode 0: D_new (u_accumulate 0: =, 1: +=) rho E cos V / pi of the light bound at BINDING_UBO_LIGHT
// (with its shadow maps) at every element: the light's direct radiance as the element reflects it,
// the "emission" the element shoots on (PatchModel.h punctualDirectRadiance is the CPU's unshadowed
// version). 1: on u_receivers, the change since D shot into the solution as unshot radiosity.
uniform int u_accumulate;
uniform int u_receivers;
void main() {
    uint ei = linearInvocation();
    if (ei >= u_count) return;
    RadElementGpu e = u_elements[ei];
    ivec2 t = texelOf(e);
    if (u_mode == 0) {
        // Every element receives, zero-area ghosts too: the display filters their radiosity.
        uint body = e.info.z;
        vec3 x = (radWorldFromObject(body, false) * vec4(e.position.xyz, 1.0)).xyz;
        vec3 n = normalize(radNormalToWorld(body, false, u_quads[e.info.x].normal.xyz));
        vec3 l;
        vec3 irradiance = punctualIrradiance(u_light, x, l);
        float cosTheta = max(dot(n, l), 0.0);
        vec4 d = vec4(0.0);
        if (cosTheta > 0.0 && max(irradiance.r, max(irradiance.g, irradiance.b)) > 0.0)
            d.rgb = e.albedo.rgb * irradiance * (cosTheta * kInvPi) * shadowVisibility(u_light, x, n);
        if (u_accumulate != 0) d += imageLoad(i_lightNew, t);
        imageStore(i_lightNew, t, d);
        return;
    }
    bool moving = radBodyMoving(e.info.z);
    if ((u_receivers == RAD_RECEIVERS_STATIC && moving) || (u_receivers == RAD_RECEIVERS_MOVING && !moving)) return;
    vec4 dNew = imageLoad(i_lightNew, t);
    vec4 delta = vec4((dNew - imageLoad(i_light, t)).rgb, 0.0);
    imageStore(i_total, t, imageLoad(i_total, t) + delta);
    imageStore(i_unshot, t, imageLoad(i_unshot, t) + delta);
    imageStore(i_light, t, vec4(dNew.rgb, 0.0));
}
#endif
