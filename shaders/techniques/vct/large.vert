// Rauwendaal 2013 section 4.1.3, hybrid pass 2: the "large" triangles pass 1 appended are drawn by
// one indirect draw. GL has no index buffer per object instance here (one mesh may be placed by
// several objects), so pass 1 appends (vertex index, object index) pairs and this stage pulls the
// vertex from the scene's vertex buffer: an index buffer with vertex pulling. Outputs as
// voxelize.vert, for the fragment-parallel geometry and fragment stages.
#include "common/scene.glsl"
#include "techniques/vct/volume.glsl"

struct SceneVertex { float px, py, pz, nx, ny, nz, u, v; };  // render/SceneGpu.cpp's Vertex (32 bytes)
layout(std430, binding = BINDING_SSBO_TECH2) readonly buffer SceneVertices { SceneVertex s_vertices[]; };
// Pairs (vertex, object) per corner, three per large triangle.
layout(std430, binding = BINDING_SSBO_TECH3) readonly buffer LargeTriangles { uvec2 l_corners[]; };

out vec3 vg_posWorld;
out vec3 vg_normal;
out vec2 vg_uv;
flat out uint vg_object;
flat out uint vg_vertex;

void main() {
    uvec2 c = l_corners[gl_VertexID];
    SceneVertex sv = s_vertices[c.x];
    ObjectGpu o = u_objects[c.y];
    vec4 p = o.worldFromObject * vec4(sv.px, sv.py, sv.pz, 1.0);
    vg_posWorld = p.xyz;
    vg_normal = mat3(o.normalFromObject) * vec3(sv.nx, sv.ny, sv.nz);
    vg_uv = vec2(sv.u, sv.v);
    vg_object = c.y;
    vg_vertex = c.x;
    gl_Position = u_vct.voxelFromWorld * p;
}
