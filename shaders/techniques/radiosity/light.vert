// van de Hoef 2013 sec. 4.1: area lights are emitting patches. Draws every area light's rectangle
// (two triangles, p0 p1 p3 and p1 p2 p3, six vertices per light, no vertex buffer) with the
// interface of render/scene.vert, so the hemicube and display passes treat it like scene geometry;
// v_object carries RAD_LIGHT_OBJECT_BIT | quad index, or RAD_SKIP_OBJECT when u_filter excludes the
// light's body.
#include "common/scene.glsl"
#include "techniques/radiosity/patch.glsl"

uniform uint u_firstLightQuad;
uniform int u_old;     // 1: the bodies before this frame's motion
uniform int u_filter;  // DrawFilter: 0 all, 1 static bodies only, 2 moving only

out vec3 v_posWorld;
out vec3 v_normalWorld;
out vec2 v_uv;
flat out uint v_object;

const int kCorner[6] = int[6](0, 1, 3, 1, 2, 3);

void main() {
    uint quad = u_firstLightQuad + uint(gl_VertexID / 6);
    RadQuadGpu q = u_quads[quad];
    int c = kCorner[gl_VertexID % 6];
    vec3 p = c == 0 ? q.p0.xyz : c == 1 ? q.p1.xyz : c == 2 ? q.p2.xyz : q.p3.xyz;
    bool old = u_old != 0;
    vec4 w = radWorldFromObject(q.info.x, old) * vec4(p, 1.0);
    v_posWorld = w.xyz;
    v_normalWorld = radNormalToWorld(q.info.x, old, q.normal.xyz);
    v_uv = vec2(0.0);
    bool moving = radBodyMoving(q.info.x);
    v_object = (u_filter == 1 && moving) || (u_filter == 2 && !moving) ? RAD_SKIP_OBJECT : (RAD_LIGHT_OBJECT_BIT | quad);
    gl_Position = u_view.clipFromWorld * w;
}
