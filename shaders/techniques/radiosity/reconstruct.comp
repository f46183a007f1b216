// van de Hoef 2013: the per-element reconstruction shaders ("gathering shot radiosity", sec. 4.3:
// one thread per receiving element, coherent writes). For each shooter s of the batch:
//   visibility: the surface ID of the shooter's ID hemicube in the direction of e, the four nearest
//     pixels (sec. 5.2.1; visibilitySamples = 1 takes the nearest only), compared with e's surface;
//   F_se: the disk approximation of Eq. 2.2.7, split into sub-disks when A_s / r^2 exceeds
//     ffSubdivideRatio (sec. 4.3.3, the adaptive form-factor subdivision);
//   Delta B_e = rho_e R_s A_s F_se (Eq. 2.2.8; formFactor() returns A_s F_se), added to B_e and Bu_e.
// R_s by RAD_SHOOT_* (radiosity_shared.h):
//   UNSHOT (Alg. 4.2), TOTAL (Alg. 4.3 line 13 / Alg. 4.4 line 15), NEG_SHOT (Alg. 4.3 line 3, old
//   hemicube), INCREMENTAL (Alg. 4.3's four visibility cases, old and new hemicube), CROSS (Alg. 4.5,
//   with R_old = -shot + P(C, s, e) and R_new = total - P(C, s', e): the signs of Eq. 3.3.1; the
//   printed Alg. 4.5 adds P at the new position, which would brighten the new shadow).
// PROJECTEDRADIOSITY: gridSize^2 rays from e through cells of s, each REPROJECTed with the back
// depth hemicube (sec. 4.5.2) and sampling the back shot hemicube bilinearly within its face; their
// average is P(C, s, e), the area-weighted radiosity behind s (Eq. 3.3.2), or with RAD_CROSS_FF_WEIGHTS
// (setting crossWeights=formFactor, bounce's) each ray weighted by its cell's form factor seen from e,
// cos_e cos_s / (pi r^2 + A_cell): the split of F_se among what lies behind s that Eq. 3.3.1's
// transitivity means, which the area average equals only where s is small against its distance to e.
#include "techniques/radiosity/patch.glsl"
#include "techniques/radiosity/hemicube.glsl"

layout(local_size_x = 64) in;
// After the local size: dispatch.glsl reads gl_WorkGroupSize.
#include "common/dispatch.glsl"

layout(std140, binding = BINDING_UBO_PASS) uniform RadPassBlock { RadPassUniforms u_pass; };
layout(std430, binding = BINDING_SSBO_RAD_ELEMENTS) readonly buffer RadElementBlock { RadElementGpu u_elements[]; };
layout(std430, binding = BINDING_SSBO_RAD_SHOOTERS) readonly buffer RadShooterBlock { RadShooterGpu u_shooters[]; };
layout(binding = BINDING_IMG0, rgba32f) uniform image2D i_total;
layout(binding = BINDING_IMG1, rgba32f) uniform image2D i_unshot;
layout(binding = BINDING_TEX_TECH0) uniform usampler2DArray s_idOld;  // role 0 (the only one but INCREMENTAL/CROSS)
layout(binding = BINDING_TEX_TECH1) uniform usampler2DArray s_idNew;  // role 1
layout(binding = BINDING_TEX_TECH2) uniform sampler2DArray s_backOld; // role 2, resolved
layout(binding = BINDING_TEX_TECH3) uniform sampler2DArray s_backNew; // role 3, resolved

const float kPi = 3.14159265358979;

// Record index of shooter k's hemicube in role r (RadiositySystem::recordIndex).
uint recordOf(uint k, uint role) { return u_pass.slots.y + role * uint(RAD_MAX_BATCH) + k; }

bool visibleOld(uint k, vec3 target, uint surface) {
    RadHemicubeGpu h = u_hemicubes[recordOf(k, 0u)];
    int R = int(u_pass.counts.y), face;
    vec2 px;
    if (!hcProject(h, target - h.origin.xyz, float(R), face, px)) return false;
    ivec2 size = hcFaceSize(face, R);
    int layer = int(k) * 5 + face;
    if (u_pass.modes.w == 1u) return texelFetch(s_idOld, ivec3(clamp(ivec2(px), ivec2(0), size - 1), layer), 0).r == surface + 1u;
    ivec2 base = ivec2(floor(px - 0.5));
    for (int j = 0; j < 4; ++j) {
        ivec2 p = clamp(base + ivec2(j & 1, j >> 1), ivec2(0), size - 1);
        if (texelFetch(s_idOld, ivec3(p, layer), 0).r == surface + 1u) return true;
    }
    return false;
}
bool visibleNew(uint k, vec3 target, uint surface) {
    RadHemicubeGpu h = u_hemicubes[recordOf(k, 1u)];
    int R = int(u_pass.counts.y), face;
    vec2 px;
    if (!hcProject(h, target - h.origin.xyz, float(R), face, px)) return false;
    ivec2 size = hcFaceSize(face, R);
    int layer = int(k) * 5 + face;
    if (u_pass.modes.w == 1u) return texelFetch(s_idNew, ivec3(clamp(ivec2(px), ivec2(0), size - 1), layer), 0).r == surface + 1u;
    ivec2 base = ivec2(floor(px - 0.5));
    for (int j = 0; j < 4; ++j) {
        ivec2 p = clamp(base + ivec2(j & 1, j >> 1), ivec2(0), size - 1);
        if (texelFetch(s_idNew, ivec3(p, layer), 0).r == surface + 1u) return true;
    }
    return false;
}

// Eq. 2.2.7 (disk approximation) from shooter s placed with old or new bodies to point x, normal n.
float formFactor(RadShooterGpu s, bool old, vec3 x, vec3 n) {
    RadQuadGpu q = u_quads[s.info.x];
    mat4 M = radWorldFromObject(s.info.y, old);
    vec3 ns = radNormalToWorld(s.info.y, old, s.normal.xyz);
    vec3 c = (M * vec4(s.position.xyz, 1.0)).xyz;
    float area = s.position.w;
    vec3 d = x - c;
    float r2 = dot(d, d);
    int sub = area > u_pass.params.x * r2 ? int(u_pass.params.y) : 1;
    float m = float(sub * sub), sum = 0.0;
    for (int j = 0; j < sub; ++j)
        for (int i = 0; i < sub; ++i) {
            vec3 y = c;
            if (sub > 1) {
                vec2 st = mix(s.rect.xy, s.rect.zw, (vec2(i, j) + 0.5) / float(sub));
                y = (M * vec4(radPointAt(q, st), 1.0)).xyz;
            }
            vec3 dy = x - y;
            float ry2 = max(dot(dy, dy), 1e-12);
            vec3 w = dy * inversesqrt(ry2);
            float cs = dot(ns, w), ce = -dot(n, w);
            if (cs > 0.0 && ce > 0.0) sum += cs * ce / (kPi * ry2 + area / m);
        }
    return area * sum / m;
}

// Bilinear sample of back hemicube (role 2 old, 3 new) of shooter k in direction d, within its face.
vec4 sampleBack(uint k, bool old, vec3 d) {
    RadHemicubeGpu h = u_hemicubes[recordOf(k, old ? 2u : 3u)];
    int R = int(u_pass.counts.z), face;
    vec2 px;
    if (!hcProject(h, d, float(R), face, px)) return vec4(0.0, 0.0, 0.0, 1e4);
    vec2 size = vec2(hcFaceSize(face, R));
    px = clamp(px, vec2(0.5), size - 0.5);  // no filtering across face edges (sec. 4.5.2)
    vec3 c = vec3(px / float(R), float(int(k) * 5 + face));
    return old ? texture(s_backOld, c) : texture(s_backNew, c);
}

// PROJECTEDRADIOSITY(s, e) of Alg. 4.5: P(C, s, e) of Eq. 3.3.2 by gridSize^2 reprojected rays.
vec3 projectedRadiosity(uint k, RadShooterGpu s, bool old, vec3 x, vec3 n) {
    RadQuadGpu q = u_quads[s.info.x];
    mat4 M = radWorldFromObject(s.info.y, old);
    vec3 ns = radNormalToWorld(s.info.y, old, s.normal.xyz);
    RadHemicubeGpu h = u_hemicubes[recordOf(k, old ? 2u : 3u)];
    int g = int(u_pass.counts.w);
    bool ffWeights = (u_pass.slots.w & RAD_CROSS_FF_WEIGHTS) != 0u;
    float cellArea = s.position.w / float(g * g);
    vec3 total = vec3(0.0);
    float weights = 0.0;
    for (int j = 0; j < g; ++j)
        for (int i = 0; i < g; ++i) {
            vec2 st = mix(s.rect.xy, s.rect.zw, (vec2(i, j) + 0.5) / float(g));
            vec3 cell = (M * vec4(radPointAt(q, st), 1.0)).xyz;
            vec3 r = normalize(cell - x);
            vec3 dir = r;
            if ((u_pass.slots.w & RAD_CROSS_REPROJECT) != 0u) {
                // REPROJECT: the depth seen from the patch centre along r (r' parallel to r), taken as
                // the distance along r from the ray's crossing of the patch.
                float depth = sampleBack(k, old, r).a;
                dir = cell + r * depth - h.origin.xyz;
            }
            float w = 1.0;
            if (ffWeights) {
                vec3 d = cell - x;
                w = max(dot(n, r), 0.0) * max(-dot(ns, r), 0.0) / (kPi * dot(d, d) + cellArea);
            }
            total += w * sampleBack(k, old, dir).rgb;
            weights += w;
        }
    return weights > 0.0 ? total / weights : vec3(0.0);
}

void main() {
    uint ei = linearInvocation();
    if (ei >= u_pass.counts.x) return;
    RadElementGpu e = u_elements[ei];
    if (e.albedo.r + e.albedo.g + e.albedo.b <= 0.0) return;  // emitters reflect nothing
    bool moving = radBodyMoving(e.info.z);
    uint receivers = u_pass.modes.y;
    if ((receivers == uint(RAD_RECEIVERS_STATIC) && moving) || (receivers == uint(RAD_RECEIVERS_MOVING) && !moving)) return;
    bool recvOld = u_pass.slots.z != 0u;
    vec3 x = (radWorldFromObject(e.info.z, recvOld) * vec4(e.position.xyz, 1.0)).xyz;
    vec3 n = radNormalToWorld(e.info.z, recvOld, u_quads[e.info.x].normal.xyz);
    uint mode = u_pass.modes.x;
    uint surface = u_quads[e.info.x].info.w;
    vec3 dB = vec3(0.0);
    for (uint k = 0u; k < u_pass.modes.z; ++k) {
        RadShooterGpu s = u_shooters[u_pass.slots.x + k];
        if (u_quads[s.info.x].info.w == surface) continue;  // a planar surface does not see itself
        if (mode == uint(RAD_SHOOT_UNSHOT) || mode == uint(RAD_SHOOT_TOTAL)) {
            if (!visibleNew(k, x, surface)) continue;
            dB += (mode == uint(RAD_SHOOT_UNSHOT) ? s.unshot.rgb : s.total.rgb) * formFactor(s, false, x, n);
        } else if (mode == uint(RAD_SHOOT_NEG_SHOT)) {
            if (!visibleOld(k, x, surface)) continue;
            dB -= s.shot.rgb * formFactor(s, true, x, n);
        } else if (mode == uint(RAD_SHOOT_INCREMENTAL)) {
            bool vo = visibleOld(k, x, surface), vn = visibleNew(k, x, surface);
            if (!vo && !vn) continue;
            vec3 R = vo && !vn ? -s.shot.rgb : (!vo && vn ? s.total.rgb : s.unshot.rgb);
            // Static shooters: the old and new positions coincide, one form factor serves both.
            dB += R * formFactor(s, false, x, n);
        } else {  // RAD_SHOOT_CROSS
            // Inserting M (sec. 4.5.2, after the initial solution without it) has no old position.
            if (u_pass.params.w == 0.0 && visibleOld(k, x, surface))
                dB += (-s.shot.rgb + projectedRadiosity(k, s, true, x, n)) * formFactor(s, true, x, n);
            if (visibleNew(k, x, surface))
                dB += (s.total.rgb - projectedRadiosity(k, s, false, x, n)) * formFactor(s, false, x, n);
        }
    }
    dB *= e.albedo.rgb;
    if (all(equal(dB, vec3(0.0)))) return;
    ivec2 t = ivec2(e.info.y & 0xFFFFu, e.info.y >> 16);
    imageStore(i_total, t, imageLoad(i_total, t) + vec4(dB, 0.0));
    imageStore(i_unshot, t, imageLoad(i_unshot, t) + vec4(dB, 0.0));
}
