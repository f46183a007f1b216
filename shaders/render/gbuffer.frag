// G-buffer (deferred shading input). Inputs: render/scene.vert outputs, materials.
// Outputs (all linear): 0 position (xyz world, w = 1 where covered), 1 normal (xyz world shading
// normal facing the viewer for two-sided materials, w = roughness), 2 albedo (rgb; w = metallic),
// 3 emission (rgb radiance W/(m^2 sr); w = specularF0). The camera sees through the back of a
// one-sided surface (it is culled, as the reference's camera rays pass through it); shadow maps
// keep back faces, so they still occlude light, as the reference's shadow rays find them.
#include "common/scene.glsl"

in vec3 v_posWorld;
in vec3 v_normalWorld;
in vec2 v_uv;
in vec4 v_tangentWorld;
flat in uint v_object;

layout(location = 0) out vec4 o_position;
layout(location = 1) out vec4 o_normal;
layout(location = 2) out vec4 o_albedo;
layout(location = 3) out vec4 o_emission;

void main() {
    uint material = u_objects[v_object].info.x;
    MaterialGpu m = u_materials[material];
    vec3 n = normalize(v_normalWorld);
    bool twoSided = m.params.w > 0.5;
    bool back = !gl_FrontFacing;
    // Every implicit-derivative lookup comes before the discards (derivatives after a discard are
    // undefined in GLSL 4.50); the normal map is applied on the front side, then flipped, as the
    // reference does.
    vec3 albedo = materialAlbedo(material, v_uv);
    vec3 emission = materialEmission(material, v_uv);
    n = materialNormal(material, v_uv, n, v_tangentWorld);
    vec2 roughnessMetallic = materialRoughnessMetallic(material, v_uv);
    if (materialMasked(material, v_uv)) discard;
    if (back) {
        if (!twoSided) discard;
        n = -n;
    }
    o_position = vec4(v_posWorld, 1.0);
    o_normal = vec4(n, roughnessMetallic.x);
    o_albedo = vec4(albedo, roughnessMetallic.y);
    o_emission = vec4(emission, m.params.z);
}
