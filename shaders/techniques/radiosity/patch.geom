// van de Hoef 2013 sec. 4.1-4.2: per scene triangle, its quad and the (s, t) of its corners, so the
// fragment stage can read the quad's atlas region (display) or write its ID (hemicubes).
// RAD_HEMICUBE 1: layered hemicube rendering, one invocation per face (the thesis renders five
// projections; here one draw, the face chosen by gl_Layer = 5 slot + face; Alg. 4.1-4.5 hemicubes).
// RAD_HEMICUBE 0: pass-through of the camera's clip position (display).
// Inputs: render/scene.vert or light.vert. Host defines: RAD_HEMICUBE.
#include "common/scene.glsl"
#include "techniques/radiosity/patch.glsl"
#if RAD_HEMICUBE
#include "techniques/radiosity/hemicube.glsl"
layout(triangles, invocations = 5) in;
uniform uint u_hemicube;   // record in u_hemicubes
uniform int u_layerBase;   // first layer of this hemicube in the target array
uniform float u_far;       // metres
out float gl_ClipDistance[1];
#else
layout(triangles) in;
#endif
layout(triangle_strip, max_vertices = 3) out;

in vec3 v_posWorld[];
in vec3 v_normalWorld[];
in vec2 v_uv[];
flat in uint v_object[];

out vec3 g_posWorld;
out vec2 g_st;
flat out uint g_quad;
flat out vec3 g_normalWorld;
out vec2 g_uv;               // alpha mask lookup (hemicube.frag, display.frag)
flat out uint g_material;    // the object's material, RAD_NO_MATERIAL for light quads

void main() {
    if (v_object[0] == RAD_SKIP_OBJECT) return;
    vec2 st[3];
    uint quad = radTriangleQuad(v_object[0], uint(gl_PrimitiveIDIn), st);
    vec3 n = normalize(cross(v_posWorld[1] - v_posWorld[0], v_posWorld[2] - v_posWorld[0]));
    if (dot(n, v_normalWorld[0] + v_normalWorld[1] + v_normalWorld[2]) < 0.0) n = -n;
#if RAD_HEMICUBE
    RadHemicubeGpu h = u_hemicubes[u_hemicube];
    int face = gl_InvocationID;
#endif
    uint material = (v_object[0] & RAD_LIGHT_OBJECT_BIT) != 0u ? RAD_NO_MATERIAL : u_objects[v_object[0]].info.x;
    for (int k = 0; k < 3; ++k) {
        g_posWorld = v_posWorld[k];
        g_uv = v_uv[k];
        g_material = material;
        g_st = st[k];
        g_quad = quad;
        g_normalWorld = n;
#if RAD_HEMICUBE
        float cd;
        gl_Position = hcClip(h, face, v_posWorld[k], u_far, cd);
        gl_ClipDistance[0] = cd;
        gl_Layer = u_layerBase + face;
#else
        gl_Position = gl_in[k].gl_Position;
#endif
        EmitVertex();
    }
    EndPrimitive();
}
