// Screen-space binary voxelization (Nichols 2010 §5.3.3): passes each triangle through unchanged and
// gives its fragments the triangle's view-depth range, so voxelize.frag can keep a fragment's depth
// footprint within the triangle. A fragment's footprint (its depth +- half the depth change over one
// column) reaches half a column beyond the triangle's edge; for a surface seen edge-on (a shelf board
// at eye level) that is tens of centimetres of depth in front of or behind the real surface, which
// blocked rays passing just by it (ScreenVoxelsGpuTest.FootprintsStayWithinTheirTriangles).
// Inputs: scene.vert's outputs, u_voxels. Outputs: world position, flat view-depth range (m).
#include "techniques/screen_voxels/screen_voxels_shared.h"
layout(triangles) in;
layout(triangle_strip, max_vertices = 3) out;
layout(std140, binding = BINDING_UBO_VOXELS) uniform VoxelBlock { ScreenVoxelsGpu u_voxels; };
in vec3 v_posWorld[];
out vec3 g_posWorld;
flat out vec2 g_depthRange;

void main() {
    float z0 = -(u_voxels.viewFromWorld * vec4(v_posWorld[0], 1.0)).z;
    float z1 = -(u_voxels.viewFromWorld * vec4(v_posWorld[1], 1.0)).z;
    float z2 = -(u_voxels.viewFromWorld * vec4(v_posWorld[2], 1.0)).z;
    vec2 range = vec2(min(z0, min(z1, z2)), max(z0, max(z1, z2)));
    for (int i = 0; i < 3; ++i) {
        gl_Position = gl_in[i].gl_Position;
        g_posWorld = v_posWorld[i];
        g_depthRange = range;
        EmitVertex();
    }
    EndPrimitive();
}
