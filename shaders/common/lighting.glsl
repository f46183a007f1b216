// Direct light from bounce's four light types (docs/scene.md "Lights"), with shadow-map visibility.
//   point:       E = I cos(theta) / r^2
//   spot:        I(alpha) = I0 cos^n(alpha) for alpha < cutoff (cos clamped at 0), else 0
//   directional: E = E_perp cos(theta)
//   area:        Lambertian rectangle of radiance L (its texture's mean: techniques other than
//                area-light shade it uniformly), emitting from the side of cross(edgeU, edgeV) or, when
//                two-sided (AREA_TWO_SIDED), from both; diffuse irradiance from the exact polygon
//                (Lambert's contour) formula E = L/2 |sum_i theta_i (n . gamma_i)| after clipping the
//                rectangle to the receiver's hemisphere, which holds on either side of the light;
//                visibility from the centre.
// Inputs: u_light (BINDING_UBO_LIGHT), s_shadow / s_shadowCube (BINDING_TEX_SHADOW[_CUBE]).
#include "common/shared.h"
#include "common/constants.glsl"

layout(std140, binding = BINDING_UBO_LIGHT) uniform LightBlock { LightGpu u_light; };
layout(binding = BINDING_TEX_SHADOW) uniform sampler2DShadow s_shadow;
layout(binding = BINDING_TEX_SHADOW_CUBE) uniform samplerCube s_shadowCube;

int lightType(LightGpu L) { return int(L.position.w + 0.5); }

// Radiant intensity (W/sr) towards x divided by r^2, or E_perp for directional lights: the
// irradiance at x on a surface facing the light. l receives the unit direction to the light.
vec3 punctualIrradiance(LightGpu L, vec3 x, out vec3 l) {
    int type = lightType(L);
    if (type == LIGHT_DIRECTIONAL) {
        l = -normalize(L.direction.xyz);
        return L.emission.rgb;
    }
    vec3 d = L.position.xyz - x;
    float r2 = max(dot(d, d), 1e-12);
    l = d * inversesqrt(r2);
    vec3 intensity = L.emission.rgb;
    if (type == LIGHT_SPOT) {
        float cosAlpha = dot(-l, normalize(L.direction.xyz));
        if (cosAlpha < L.direction.w || cosAlpha <= 0.0) return vec3(0.0);
        intensity *= pow(cosAlpha, L.emission.w);
    }
    return intensity / r2;
}

// x's position in cascade k of L's 2D map: (cascade uv, depth).
vec3 shadowCascadeUvz(LightGpu L, vec4 k, vec3 x) {
    vec4 clip = L.shadowClipFromWorld * vec4(x, 1.0);
    vec3 uvz = clip.xyz / clip.w * 0.5 + 0.5;
    return vec3((uvz.xy - k.xy) * k.z, uvz.z);
}

// Visibility of light L from x (normal n) through the given maps (a pass that samples several
// lights at once binds each light's maps to its own units). 2D maps (docs/rendering.md "Shadows"):
// - the first cascade whose tile holds x's PCF kernel (finest first; the last, the whole scene, holds
//   every point of the scene);
// - looked up from x offset along n by the constant shadowBias plus shadowOrigin.w texels of that
//   cascade times sin(incidence) (the normal offset, scaled by the texel's world size);
// - each tap compared at the receiver's own plane's depth there (receiver-plane depth bias: the
//   plane through x with normal n, projected into the map, gives dz/duv; slope-scaled bias computed
//   from the normal, so a planar receiver never shadows itself at any kernel radius), less the
//   plane's fall to the lowest of the four texel centres the bilinear compare reads (known from the
//   lookup's position in its texel: on average half a texel's slope) plus kBilinearSlackMargin of
//   one texel's slope; slopes past kMaxReceiverSlope (grazing, where cos(theta) leaves almost no
//   light) are clamped. Directional lights only: spot lights keep the map's polygon offset
//   (render/LightSet.cpp says why);
// - the taps weighted by a tent, (r + 1 - |i|)(r + 1 - |j|): with the bilinear compares a kernel that
//   falls off smoothly, narrower than the box of the same reach (the reference's sun is a delta light).
const float kMaxReceiverSlope = 10.0;  // tan(84 degrees): depth per lateral distance, bounce's choice
// Margin of the bilinear slack, in one texel's slope: the map's depths are rounded and the normal is
// interpolated; with none the grazing walls of atrium show acne (docs/techniques/direct.md).
const float kBilinearSlackMargin = 0.25;
float shadowVisibilityFrom(LightGpu L, sampler2DShadow map2D, samplerCube mapCube, vec3 x, vec3 n) {
    int kind = int(L.edgeU.w + 0.5);
    if (kind == 0) return 1.0;
    if (kind == 2) {
        vec3 p = x + n * L.edgeV.w;  // normal-offset bias (metres)
        vec3 d = p - L.shadowOrigin.xyz;
        float stored = texture(mapCube, d).r * L.shadowParams.x;
        return length(d) <= stored ? 1.0 : 0.0;
    }
    bool directional = lightType(L) == LIGHT_DIRECTIONAL;
    vec3 toLight = directional ? -normalize(L.direction.xyz) : normalize(L.position.xyz - x);
    float cosTheta = clamp(dot(n, toLight), -1.0, 1.0);
    float sinTheta = sqrt(max(1.0 - cosTheta * cosTheta, 0.0));
    float size = L.shadowParams.y;
    int radius = int(L.shadowParams.z + 0.5);
    int count = clamp(int(L.shadowParams.w + 0.5), 1, SHADOW_MAX_CASCADES);
    float margin = (float(radius) + 1.0) / size;  // the kernel's reach in a tile's uv
    int cascade = count - 1;
    vec3 uvz = vec3(0.0), p = x;
    float texelWorld = 0.0;
    for (int c = 0; c < count; ++c) {
        vec4 k = L.shadowCascades[c];
        texelWorld = directional ? k.w : k.w * distance(x, L.position.xyz);
        p = x + n * (L.edgeV.w + L.shadowOrigin.w * texelWorld * sinTheta);
        uvz = shadowCascadeUvz(L, k, p);
        cascade = c;
        if (all(greaterThanEqual(uvz.xy, vec2(margin))) && all(lessThanEqual(uvz.xy, vec2(1.0 - margin)))) break;
    }
    if (any(lessThan(uvz.xy, vec2(0.0))) || any(greaterThan(uvz.xy, vec2(1.0))) || uvz.z > 1.0) return 1.0;
    float texel = 1.0 / size;
    // Receiver plane: two tangents one texel long, projected; dz/duv solves the 2 x 2 system.
    vec4 k = L.shadowCascades[cascade];
    vec3 t1 = normalize(cross(n, abs(n.y) < 0.99 ? vec3(0.0, 1.0, 0.0) : vec3(1.0, 0.0, 0.0)));
    vec3 t2 = cross(n, t1);
    vec3 a = shadowCascadeUvz(L, k, p + t1 * texelWorld) - uvz;
    vec3 b = shadowCascadeUvz(L, k, p + t2 * texelWorld) - uvz;
    float det = a.x * b.y - a.y * b.x;
    float zPerTexel = abs(shadowCascadeUvz(L, k, p + toLight * texelWorld).z - uvz.z);  // depth of one texel's distance
    float maxSlope = kMaxReceiverSlope * zPerTexel / texel;
    vec2 slope = abs(det) > 1e-20 ? vec2(a.z * b.y - b.z * a.y, b.z * a.x - a.z * b.x) / det : vec2(0.0);
    // Directional maps only: spot maps keep the polygon offset (render/LightSet.cpp).
    slope = directional ? clamp(slope, vec2(-maxSlope), vec2(maxSlope)) : vec2(0.0);
    // The lookup's position between the four texel centres the compare reads (the same for every
    // tap: they are whole texels apart); the plane's lowest depth among them lies `slack` below.
    vec2 within = fract(uvz.xy * size - 0.5);
    vec2 fall = mix(-slope * (1.0 - within), slope * within, step(0.0, slope));
    float slack = (fall.x + fall.y + kBilinearSlackMargin * (abs(slope.x) + abs(slope.y))) * texel;
    // The cascade's tile in the atlas (2 x 2 with cascades, render/ShadowCascades.h); taps stay inside it.
    float tiles = count > 1 ? 2.0 : 1.0;
    vec2 tile = vec2(float(cascade % 2), float(cascade / 2));
    float sum = 0.0;
    for (int j = -radius; j <= radius; ++j)
        for (int i = -radius; i <= radius; ++i) {
            vec2 offset = vec2(i, j) * texel;
            vec2 local = clamp(uvz.xy + offset, vec2(0.5 * texel), vec2(1.0 - 0.5 * texel));
            float z = uvz.z + dot(slope, offset) - slack;
            float weight = float(radius + 1 - abs(i)) * float(radius + 1 - abs(j));
            sum += weight * textureLod(map2D, vec3((tile + local) / tiles, z), 0.0);
        }
    float weights = float((radius + 1) * (radius + 1)) * float((radius + 1) * (radius + 1));  // (sum of 1..r+1..1)^2
    return sum / weights;
}

float shadowVisibility(LightGpu L, vec3 x, vec3 n) { return shadowVisibilityFrom(L, s_shadow, s_shadowCube, x, n); }

bool areaTwoSided(LightGpu L) { return (int(L.area.w + 0.5) & AREA_TWO_SIDED) != 0; }

// Irradiance at x (normal n) from the rectangle, unshadowed: from its emitting face, or from the face
// on x's side for a two-sided light (both faces emit the same radiance).
vec3 areaIrradiance(LightGpu L, vec3 x, vec3 n) {
    vec3 nl = normalize(cross(L.edgeU.xyz, L.edgeV.xyz));
    vec3 c = L.position.xyz;
    float side = dot(x - c, nl);
    if (side == 0.0 || (side < 0.0 && !areaTwoSided(L))) return vec3(0.0);  // in its plane, or behind a one-sided light
    vec3 hu = 0.5 * L.edgeU.xyz, hv = 0.5 * L.edgeV.xyz;
    vec3 quad[4] = vec3[4](c - hu - hv - x, c + hu - hv - x, c + hu + hv - x, c - hu + hv - x);
    // Sutherland-Hodgman clip against the receiver's tangent plane (keep dot(n, v) >= 0).
    vec3 poly[5];
    int count = 0;
    for (int i = 0; i < 4; ++i) {
        vec3 a = quad[i], b = quad[(i + 1) % 4];
        float da = dot(n, a), db = dot(n, b);
        if (da >= 0.0 && count < 5) poly[count++] = a;
        if ((da >= 0.0) != (db >= 0.0) && count < 5) poly[count++] = a + (b - a) * (da / (da - db));
    }
    if (count < 3) return vec3(0.0);
    float sum = 0.0;
    for (int i = 0; i < count; ++i) {
        vec3 a = normalize(poly[i]), b = normalize(poly[(i + 1) % count]);
        float cosTheta = clamp(dot(a, b), -1.0, 1.0);
        vec3 g = cross(a, b);
        float len = length(g);
        if (len > 1e-9) sum += acos(cosTheta) * dot(n, g / len);
    }
    return L.emission.rgb * 0.5 * abs(sum);
}
