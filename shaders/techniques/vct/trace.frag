// Rauwendaal 2013 sections 6.3-6.5 and 7.2: the full-screen pass over the camera G-buffer. Per pixel:
// six 60-degree cones in the normal's frame (Eq. 6.8; weights pi/4 and 3 pi/20, Eq. 6.9) give the
// diffuse interreflection L = rho / pi sum_k W_k L_k (Eq. 6.14) and the ambient accessibility
// O = 1 / pi sum_k W_k V_k (Eq. 6.7); one specular cone about the mirror direction, aperture from the
// GGX roughness, weighted by Schlick's Fresnel term (the thesis multiplies by the G-buffer specular
// colour). The origin of the diffuse/AO cones is shifted by f voxels along the normal (section 6.1.1).
// Two programs, timed as Fig. 7.4's stages: VCT_PART 1 diffuse + AO (and the debug views, VCT_DEBUG_*),
// VCT_PART 2 specular, added by blending. Output: indirect radiance W/(m^2 sr), RGBA32F.
#include "common/constants.glsl"
#include "common/frame.glsl"
#include "common/gbuffer.glsl"
#include "techniques/vct/volume.glsl"
#include "techniques/vct/cone.glsl"

layout(location = 0) out vec4 o_radiance;
in vec2 v_uv;

// Eq. 6.8, normal along +Y.
const vec3 kConeDirections[6] = vec3[6](vec3(0.0, 1.0, 0.0), vec3(0.0, 0.5, 0.866025), vec3(0.823639, 0.5, 0.267617),
                                        vec3(0.509037, 0.5, -0.700629), vec3(-0.509037, 0.5, -0.700629),
                                        vec3(-0.823639, 0.5, 0.267617));
// Eq. 6.9: the central cone integrates cos over 30 degrees (pi/4), each ring cone a fifth of the rest.
const float kConeWeights[6] = float[6](0.785398163, 0.471238898, 0.471238898, 0.471238898, 0.471238898, 0.471238898);
const float kSinHalf60 = 0.5;
const float kConeRatio60 = 1.0;  // sin(30) / (1 - sin(30))
// Narrowest specular cone: 1 degree (a 0-degree cone is a ray, section 6.5; the step is then one voxel).
const float kMinSpecularAperture = 0.0174533;  // radians


// Marches the camera ray through level `level`; returns (value, hit).
vec4 debugMarch(vec3 eyeTex, vec3 dirTex, int level, bool radiance) {
    float texel = exp2(float(level)) * u_vct.grid.y;
    // Clip the ray to the unit cube.
    vec3 inv = 1.0 / (dirTex + vec3(1e-9));
    vec3 t0 = (vec3(0.0) - eyeTex) * inv, t1 = (vec3(1.0) - eyeTex) * inv;
    float tNear = max(max(min(t0.x, t1.x), min(t0.y, t1.y)), max(min(t0.z, t1.z), 0.0));
    float tFar = min(min(max(t0.x, t1.x), max(t0.y, t1.y)), max(t0.z, t1.z));
    for (float t = tNear; t < tFar; t += 0.5 * texel) {
        vec3 p = eyeTex + dirTex * t;
        vec4 s = textureLod(s_alpha, p, float(level));
        if (s.a > 0.5) {
            if (!radiance) return vec4(1.0);
            // The radiance seen looking along the ray (the cone direction of voxelFetch), straight colour.
            vec4 v = voxelFetch(p, float(level), dirTex);
            return vec4(v.rgb / max(v.a, 1e-6), 1.0);
        }
    }
    return vec4(0.0);
}

void main() {
    ivec2 pixel = ivec2(gl_FragCoord.xy);
    float N = u_vct.grid.x;
    float voxSize = u_vct.grid.y;  // one level-0 voxel in texture units
    float metresToTexture = 1.0 / (u_vct.grid.z * N);
    float maxDist = u_vct.cone.z * metresToTexture, aoDist = u_vct.cone.w * metresToTexture;
#if VCT_PART == 1
    int view = int(u_vct.debug.x + 0.5);
    if (view == VCT_DEBUG_SLICE) {
        vec3 p = vec3(v_uv, u_vct.debug.z);
        o_radiance = vec4(voxelFetch(p, u_vct.debug.y, vec3(0.0, 0.0, -1.0)).rgb, 1.0);
        return;
    }
    if (view == VCT_DEBUG_OCCUPANCY || view == VCT_DEBUG_RADIANCE) {
        vec4 ndc = vec4(v_uv * 2.0 - 1.0, 1.0, 1.0);
        vec4 farWorld = u_frame.worldFromClip * ndc;
        vec3 eyeTex = toTexture(u_frame.eyePosition.xyz);
        vec3 dirTex = normalize(toTexture(farWorld.xyz / farWorld.w) - eyeTex);
        o_radiance = vec4(debugMarch(eyeTex, dirTex, int(u_vct.debug.y + 0.5), view == VCT_DEBUG_RADIANCE).rgb, 1.0);
        return;
    }
#endif
    Surface s = readSurface(pixel);
    if (!s.covered) {
        o_radiance = vec4(0.0);
        return;
    }
    vec3 n = s.normal;
    vec3 x = toTexture(s.position);
#if VCT_PART == 1
    // Frame with the normal along +Y.
    vec3 helper = abs(n.y) < 0.99 ? vec3(0.0, 1.0, 0.0) : vec3(1.0, 0.0, 0.0);
    vec3 tx = normalize(cross(helper, n));
    vec3 tz = cross(tx, n);
    vec3 origin = x + n * (u_vct.cone.x * voxSize);
    vec3 diffuse = vec3(0.0);
    float accessibility = 0.0;
    bool specialised = u_vct.cone2.z > 0.5;
    for (int k = 0; k < 6; ++k) {
        vec3 d = kConeDirections[k];
        vec3 dir = normalize(tx * d.x + n * d.y + tz * d.z);
        vec4 c = specialised ? coneTrace60(origin, dir, maxDist, aoDist, voxSize)
                             : coneTrace(origin, n, dir, kConeRatio60, maxDist, aoDist, voxSize, N, u_vct.cone.x,
                                         u_vct.cone.y, kSinHalf60, true, u_vct.cone.x * voxSize, dot(dir, n));
        diffuse += kConeWeights[k] * c.rgb;
        accessibility += kConeWeights[k] * c.a;
    }
    accessibility *= kInvPi;
    if (view == VCT_DEBUG_AO) {
        o_radiance = vec4(vec3(accessibility), 1.0);
        return;
    }
    o_radiance = vec4((1.0 - s.metallic) * s.albedo * kInvPi * diffuse, 1.0);
#else
    vec3 f0 = mix(vec3(s.specularF0), s.albedo, s.metallic);
    if (max(f0.r, max(f0.g, f0.b)) <= 0.0) discard;
    vec3 v = normalize(u_frame.eyePosition.xyz - s.position);
    vec3 r = reflect(-v, n);
    float alpha = s.roughness * s.roughness;
    float aperture = clamp(2.0 * atan(u_vct.cone2.y * alpha), kMinSpecularAperture, 2.0 * 1.0471976);
    float sinHalf = sin(0.5 * aperture);
    vec4 c = coneTrace(x, n, r, sinHalf / (1.0 - sinHalf), maxDist, 0.0, voxSize, N, u_vct.cone.x, u_vct.cone.y, sinHalf,
                       false, 0.0, dot(r, n));
    float cosV = clamp(dot(n, v), 0.0, 1.0);
    vec3 fresnel = f0 + (1.0 - f0) * pow(1.0 - cosV, 5.0);
    o_radiance = vec4(fresnel * c.rgb, 1.0);
#endif
}
