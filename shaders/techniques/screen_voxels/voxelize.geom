// Screen-space binary voxelization (Nichols 2010 §5.3.3): passes each triangle through unchanged and
// gives its fragments what voxelize.frag needs to set exactly the depths the triangle spans inside a
// fragment's column: the three vertices in grid pixels, each with its view depth over clip w and 1 / w
// (both affine in screen space under any projection, so the depth anywhere on the triangle's screen
// image is their ratio), and the triangle's view-depth range for the fallback.
// A fragment's footprint taken from the depth's screen derivatives (its depth +- half the change over
// one column) reaches half a column beyond the triangle's edge; for a surface seen edge-on (a shelf
// board at eye level, the top of a block above the camera) that is centimetres of depth in front of or
// behind the real surface, which blocked rays passing just by it
// (ScreenVoxelsGpuTest.FootprintsStayWithinTheirTriangles, ExactFootprintsLeaveRaysPastAnEdgeFree).
// A triangle with a vertex at or behind the camera plane (clip w <= 0) has no finite screen image:
// its fragments fall back to the derivative footprint clamped to the triangle's depth range.
// Inputs: scene.vert's outputs, u_voxels. Outputs: world position, flat vertex data, flat view-depth
// range (m).
#include "techniques/screen_voxels/screen_voxels_shared.h"
layout(triangles) in;
layout(triangle_strip, max_vertices = 3) out;
layout(std140, binding = BINDING_UBO_VOXELS) uniform VoxelBlock { ScreenVoxelsGpu u_voxels; };
in vec3 v_posWorld[];
in vec2 v_uv[];
flat in uint v_object[];
out vec3 g_posWorld;
out vec2 g_uv;              // alpha mask lookup (voxelize.frag)
flat out uint g_object;
flat out vec2 g_depthRange;
flat out vec3 g_screenX;    // vertices' grid pixel coordinates (window origin, as gl_FragCoord)
flat out vec3 g_screenY;
flat out vec3 g_depthOverW; // view depth / clip w per vertex
flat out vec3 g_invW;       // 1 / clip w per vertex; all 0 when the triangle has no finite screen image

// Clip w below which a vertex counts as at the camera plane (clip units; the near plane is far above).
const float kMinClipW = 1e-6;

void main() {
    vec3 sx, sy, dw, iw;
    bool finite = true;
    float z[3];
    for (int i = 0; i < 3; ++i) {
        vec4 c = gl_in[i].gl_Position;
        z[i] = -(u_voxels.viewFromWorld * vec4(v_posWorld[i], 1.0)).z;
        finite = finite && c.w > kMinClipW;
        float w = max(c.w, kMinClipW);
        vec2 p = (c.xy / w * 0.5 + 0.5) * u_voxels.grid.xy;
        sx[i] = p.x;
        sy[i] = p.y;
        dw[i] = z[i] / w;
        iw[i] = 1.0 / w;
    }
    vec2 range = vec2(min(z[0], min(z[1], z[2])), max(z[0], max(z[1], z[2])));
    for (int i = 0; i < 3; ++i) {
        gl_Position = gl_in[i].gl_Position;
        g_posWorld = v_posWorld[i];
        g_uv = v_uv[i];
        g_object = v_object[i];
        g_depthRange = range;
        g_screenX = sx;
        g_screenY = sy;
        g_depthOverW = dw;
        g_invW = finite ? iw : vec3(0.0);
        EmitVertex();
    }
    EndPrimitive();
}
