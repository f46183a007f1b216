// Reflective shadow map (Nichols 2010 §3.2.1, Fig. 2.1; Dachsbacher & Stamminger 2005): a light-space
// G-buffer with the flux each texel reflects. Phi_t = I(dir) * dOmega_t * rho with the texel's exact
// solid angle dOmega_t = texelArea * cos^3(angle to the axis) (the "exact per-texel solid angle" option
// of §4.2.1.2 in place of Eq. 4.4); directional lights: Phi_t = E * texelArea * rho. Patch area
// A_t = dOmega_t * d^2 / cos(theta_surface) (Eq. 4.3 with the receiver's obliquity).
// Host uniforms: u_projection (0 perspective, 1 orthographic), u_texelArea (unit-distance plane, or m^2),
// u_axis (view axis, world), u_equalSolidAngle (sr per texel under Eq. 4.4's approximation, 0 = exact). Inputs: render/scene.vert outputs, u_light (BINDING_UBO_LIGHT).
// Outputs: 0 position (xyz, w light distance), 1 normal (xyz, w patch area m^2), 2 flux (rgb W, a covered).
#include "common/scene.glsl"
#include "techniques/nichols/light.glsl"

layout(std140, binding = BINDING_UBO_LIGHT) uniform LightBlock { LightGpu u_light; };
uniform int u_projection;
uniform float u_texelArea;
uniform vec3 u_axis;
uniform float u_equalSolidAngle;

in vec3 v_posWorld;
in vec3 v_normalWorld;
in vec2 v_uv;
flat in uint v_object;

layout(location = 0) out vec4 o_position;
layout(location = 1) out vec4 o_normal;
layout(location = 2) out vec4 o_flux;

// Floor of cos(theta) in the patch area: a grazing texel's area would diverge (it is bounded by the
// neighbouring texels in reality); 0.05 caps the area at 20x the perpendicular footprint. Assumption.
const float kMinAreaCosine = 0.05;

void main() {
    uint material = u_objects[v_object].info.x;
    MaterialGpu m = u_materials[material];
    vec3 n = normalize(v_normalWorld);
    vec3 dir;
    float distance;
    if (u_projection == 1) {
        dir = normalize(u_axis);
        distance = dot(v_posWorld - u_view.eyePosition.xyz, dir);
    } else {
        vec3 d = v_posWorld - u_light.position.xyz;
        distance = length(d);
        dir = d / max(distance, 1e-12);
    }
    float cosSurface = dot(n, -dir);
    vec3 albedo = (1.0 - materialRoughnessMetallic(material, v_uv).y) * materialAlbedo(material, v_uv);
    if (materialMasked(material, v_uv)) discard;  // masked texels neither occlude nor reflect
    if (cosSurface < 0.0) {
        if (m.params.w > 0.5) {
            n = -n;
            cosSurface = -cosSurface;
        } else {
            albedo = vec3(0.0);  // back face of one-sided geometry: occludes, reflects nothing
        }
    }
    vec3 flux;
    float area;
    if (u_projection == 1) {
        flux = u_light.emission.rgb * u_texelArea * albedo;
        area = u_texelArea / max(cosSurface, kMinAreaCosine);
    } else {
        float c = max(dot(dir, normalize(u_axis)), 0.0);
        float solidAngle = u_equalSolidAngle > 0.0 ? u_equalSolidAngle : u_texelArea * c * c * c;
        flux = lightIntensity(u_light, dir) * solidAngle * albedo;
        area = solidAngle * distance * distance / max(cosSurface, kMinAreaCosine);
    }
    o_position = vec4(v_posWorld, distance);
    o_normal = vec4(n, area);
    o_flux = vec4(flux, 1.0);
}
