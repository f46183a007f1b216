// Rauwendaal 2013 section 4.1.1: the voxelizers' vertex stage, transforming scene vertices into voxel
// space ([0, N]^3, unit voxels). Outputs the world position, normal and uv for the injection
// (Eq. 7.1), the object (flat) and gl_VertexID (the global vertex index, basevertex included), which
// the hybrid classifier appends to its index buffer for pass 2.
#include "common/scene.glsl"
#include "techniques/vct/volume.glsl"

layout(location = ATTR_POSITION) in vec3 a_position;
layout(location = ATTR_NORMAL) in vec3 a_normal;
layout(location = ATTR_UV) in vec2 a_uv;
layout(location = ATTR_OBJECT_INDEX) in uint a_object;

out vec3 vg_posWorld;
out vec3 vg_normal;
out vec2 vg_uv;
flat out uint vg_object;
flat out uint vg_vertex;

void main() {
    ObjectGpu o = u_objects[a_object];
    vec4 p = o.worldFromObject * vec4(a_position, 1.0);
    vg_posWorld = p.xyz;
    vg_normal = mat3(o.normalFromObject) * a_normal;
    vg_uv = a_uv;
    vg_object = a_object;
    vg_vertex = uint(gl_VertexID);
    gl_Position = u_vct.voxelFromWorld * p;
}
