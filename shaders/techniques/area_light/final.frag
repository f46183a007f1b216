// The area-light technique's direct radiance (Nichols 2010 ch. 5): the visible emitters plus, at
// pixels no light culls (§5.3.2's per-corner and one-sided tests, repeated per pixel so that no coarse
// cell's light leaks onto a pixel that faces away), the diffuse part (1 - metallic) albedo / pi * E
// and the specular part F_Schlick(N.V) * S from the upsampled multiresolution buffers.
// Emitters are box-filtered over the pixel, as the reference's primary rays see them (an addition;
// the thesis shows its screens as rasterized): kEmitterSamples rays through the pixel meet each
// light's rectangle, read its texture's nearest level-0 texel (the reference's lookup) and count where
// nothing in the pixel's surface lies in front of the hit (its tangent plane along that ray); the
// pixel's surface fills the rest. The G-buffer's emitter is one point sample with a trilinearly
// filtered texel: on cornell-box-area the light, 70 % of the image's mean radiance and 4.5 pixels
// tall at 128^2, was 4 rows (-10 % of its light), and area-screen's colour bars blended neighbouring
// texels' primaries into pixels the reference shows pure (docs/techniques/area-light.md).
// Inputs: G-buffer, u_frame, u_pass, diffuse and specular level-0 results (BINDING_TEX_TECH0, TECH1),
// the lights' textures (BINDING_TEX_AREA_LIGHT, INPUT0..2 for lights 0..3). Output: direct radiance
// W/(m^2 sr).
#include "common/gbuffer.glsl"
#include "common/frame.glsl"
#include "common/constants.glsl"
#include "techniques/area_light/area_common.glsl"
layout(binding = BINDING_TEX_TECH0) uniform sampler2DArray s_diffuse;
layout(binding = BINDING_TEX_TECH1) uniform sampler2DArray s_specular;
layout(binding = BINDING_TEX_AREA_LIGHT) uniform sampler2D s_light0;
layout(binding = BINDING_TEX_INPUT0) uniform sampler2D s_light1;
layout(binding = BINDING_TEX_INPUT1) uniform sampler2D s_light2;
layout(binding = BINDING_TEX_INPUT2) uniform sampler2D s_light3;
uniform bool u_hasSpecular;
uniform vec4 u_emitterRect;  // window pixels (x0, y0, x1, y1) around the lights' images: rays only there
layout(location = 0) out vec4 o_radiance;

// Rays per pixel for the emitters' box filter, on an n-rooks pattern (every sixteenth of the pixel's
// rows and of its columns holds one ray): a light's horizontal or vertical edge is then found to 1/32
// of a pixel, not to the 1/8 of a 4 x 4 grid, which left cornell-box-area's light 4 % short (an
// engineering choice; 16 rays, since each tests every light).
const int kEmitterSamples = 16;
const int kRookStride = 7;  // sample k sits in column (7 k) mod 16 of row k: coprime with 16, spread
// Relative depth by which the light's hit may lie behind the pixel's surface plane and still count
// as in front of it: a light set in an opening of a ceiling is coplanar with the ceiling around it.
const float kCoplanarTolerance = 1e-3;

// The receiver's reflected radiance at pixel q (no emission): the gathered light times its BRDF.
vec3 shade(ivec2 q, Surface s) {
    if (!s.covered || culledByAllLights(s.position, s.normal) || onEmitter(s.position)) return vec3(0.0);
    vec3 e = texelFetch(s_diffuse, ivec3(q, 0), 0).rgb;
    vec3 radiance = (1.0 - s.metallic) * s.albedo * kInvPi * e;
    if (u_hasSpecular) {
        vec3 f0 = mix(vec3(s.specularF0), s.albedo, s.metallic);
        float nDotV = max(dot(s.normal, normalize(u_frame.eyePosition.xyz - s.position)), 0.0);
        vec3 fresnel = f0 + (1.0 - f0) * pow(1.0 - nDotV, 5.0);
        if (max(f0.r, max(f0.g, f0.b)) > 0.0) radiance += fresnel * texelFetch(s_specular, ivec3(q, 0), 0).rgb;
    }
    return radiance;
}

vec3 lightTexel(int i, vec2 uv) {
    // Constant sampler names in each branch: no sampler indexing (GLSL 4.50 rules).
    if (i == 0) return texelFetch(s_light0, clamp(ivec2(uv * vec2(textureSize(s_light0, 0))), ivec2(0), textureSize(s_light0, 0) - 1), 0).rgb;
    if (i == 1) return texelFetch(s_light1, clamp(ivec2(uv * vec2(textureSize(s_light1, 0))), ivec2(0), textureSize(s_light1, 0) - 1), 0).rgb;
    if (i == 2) return texelFetch(s_light2, clamp(ivec2(uv * vec2(textureSize(s_light2, 0))), ivec2(0), textureSize(s_light2, 0) - 1), 0).rgb;
    return texelFetch(s_light3, clamp(ivec2(uv * vec2(textureSize(s_light3, 0))), ivec2(0), textureSize(s_light3, 0) - 1), 0).rgb;
}

void main() {
    ivec2 p = ivec2(gl_FragCoord.xy);
    Surface s = readSurface(p);
    bool emitterPixel = s.covered && onEmitter(s.position);
    // The box filter of the emitters over the pixel.
    vec3 emitted = vec3(0.0);
    float coverage = 0.0;
    const float kWeight = 1.0 / float(kEmitterSamples);
    bool nearEmitter = all(greaterThanEqual(gl_FragCoord.xy, u_emitterRect.xy)) && all(lessThanEqual(gl_FragCoord.xy, u_emitterRect.zw));
    for (int k = 0; k < (nearEmitter ? kEmitterSamples : 0); ++k) {
        vec2 sub = gl_FragCoord.xy - 0.5 + (vec2((kRookStride * k) % kEmitterSamples, k) + 0.5) / float(kEmitterSamples);
        vec2 ndc = sub * u_frame.viewport.zw * 2.0 - 1.0;
        vec4 nearH = u_frame.worldFromClip * vec4(ndc, -1.0, 1.0), farH = u_frame.worldFromClip * vec4(ndc, 1.0, 1.0);
        vec3 o = nearH.xyz / nearH.w, d = normalize(farH.xyz / farH.w - o);
        // The pixel's surface along this ray: its tangent plane (no surface: nothing in front).
        float dn = dot(d, s.normal);
        float tSurface = s.covered && abs(dn) > 1e-6 ? dot(s.position - o, s.normal) / dn : 1e30;
        if (tSurface <= 0.0) tSurface = 1e30;
        // The nearest light this ray meets in front of the surface (its emitting side for one-sided ones).
        int hit = -1;
        float tHit = emitterPixel ? 1e30 : tSurface * (1.0 + kCoplanarTolerance);
        vec2 uvHit = vec2(0.0);
        for (int i = 0; i < int(u_pass.counts.x); ++i) {
            AreaLightGpu L = u_pass.lights[i];
            float facing = dot(d, L.normal.xyz);
            if (abs(facing) < 1e-9 || (L.centre.w < 0.5 && facing >= 0.0)) continue;  // edge-on or its back
            float t = dot(L.centre.xyz - o, L.normal.xyz) / facing;
            if (t <= 0.0 || t > tHit) continue;
            vec3 y = o + t * d - L.centre.xyz;
            vec2 uv = vec2(dot(y, L.edgeU.xyz) / (L.edgeU.w * L.edgeU.w), dot(y, L.edgeV.xyz) / (L.edgeV.w * L.edgeV.w)) + 0.5;
            if (any(lessThan(uv, vec2(0.0))) || any(greaterThan(uv, vec2(1.0)))) continue;
            hit = i;
            tHit = t;
            uvHit = uv;
        }
        if (hit < 0) continue;
        AreaLightGpu L = u_pass.lights[hit];
        emitted += kWeight * L.radiance.rgb * (L.radiance.w > 0.5 ? lightTexel(hit, uvHit) : vec3(1.0));
        coverage += kWeight;
    }
    // What fills the rest of the pixel: its own surface, or for an emitter pixel (whose surroundings
    // the G-buffer does not hold) the mean of its receiver neighbours.
    vec3 rest = shade(p, s);
    if (emitterPixel && coverage < 1.0) {
        float n = 0.0;
        for (int dy = -1; dy <= 1; ++dy)
            for (int dx = -1; dx <= 1; ++dx) {
                ivec2 q = p + ivec2(dx, dy);
                if (any(lessThan(q, ivec2(0))) || any(greaterThanEqual(q, ivec2(u_frame.viewport.xy)))) continue;
                Surface sq = readSurface(q);
                if (!sq.covered || onEmitter(sq.position)) continue;
                rest += shade(q, sq);
                n += 1.0;
            }
        rest /= max(n, 1.0);
    }
    o_radiance = vec4(emitted + (1.0 - coverage) * rest, 1.0);
}
