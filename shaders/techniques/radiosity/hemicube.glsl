// Hemicube conventions (Cohen & Greenberg 1985; van de Hoef 2013 sec. 2.2.2, 4.2), the GLSL twin of
// src/techniques/radiosity/HemicubeMath.{h,cpp}: face f looks along axis A_f with up U_f and right
// cross(A_f, U_f): (N, B), (T, N), (-T, N), (B, N), (-B, N), B = cross(T, N). A direction projects
// to (u, v) = (d.R, d.U) / (d.A); the top face holds u, v in [-1, 1] on R x R pixels, a side face
// u in [-1, 1], v in [0, 1] on rows [0, R/2) of its R x R layer.
#include "techniques/radiosity/radiosity_shared.h"

layout(std430, binding = BINDING_SSBO_RAD_HEMICUBES) buffer RadHemicubeBlock { RadHemicubeGpu u_hemicubes[]; };

vec3 hcAxis(RadHemicubeGpu h, int f) {
    if (f == 0) return h.normal.xyz;
    if (f == 1) return h.tangent.xyz;
    if (f == 2) return -h.tangent.xyz;
    if (f == 3) return h.bitangent.xyz;
    return -h.bitangent.xyz;
}
vec3 hcUp(RadHemicubeGpu h, int f) { return f == 0 ? h.bitangent.xyz : h.normal.xyz; }

// Face and continuous pixel position of direction d; false below the horizon.
bool hcProject(RadHemicubeGpu h, vec3 d, float R, out int face, out vec2 pixel) {
    float x = dot(d, h.tangent.xyz), y = dot(d, h.bitangent.xyz), z = dot(d, h.normal.xyz);
    face = 0;
    pixel = vec2(0.0);
    if (z <= 0.0) return false;
    if (z >= abs(x) && z >= abs(y)) face = 0;
    else if (abs(x) >= abs(y)) face = x > 0.0 ? 1 : 2;
    else face = y > 0.0 ? 3 : 4;
    vec3 A = hcAxis(h, face), U = hcUp(h, face);
    float a = dot(d, A);
    float u = dot(d, cross(A, U)) / a, v = dot(d, U) / a;
    pixel.x = (0.5 * u + 0.5) * R;
    pixel.y = face == 0 ? (0.5 * v + 0.5) * R : v * 0.5 * R;
    return true;
}

// Pixel rectangle of a face: [0, R) x [0, R) for the top, [0, R) x [0, R/2) for the sides.
ivec2 hcFaceSize(int face, int R) { return ivec2(R, face == 0 ? R : R / 2); }

// Clip position of world point p on face f (near n, far fr): a 90-degree frustum; the side faces
// map v in [0, 1] to NDC y in [-1, 0] (rows [0, R/2)) and clip v > 1 with gl_ClipDistance[0].
vec4 hcClip(RadHemicubeGpu h, int f, vec3 p, float fr, out float clipDistance) {
    float n = h.origin.w;
    vec3 d = p - h.origin.xyz;
    vec3 A = hcAxis(h, f), U = hcUp(h, f), Rt = cross(A, U);
    float w = dot(d, A);
    vec4 c = vec4(dot(d, Rt), dot(d, U), (fr + n) / (fr - n) * w - 2.0 * fr * n / (fr - n), w);
    clipDistance = 1.0;
    if (f != 0) {
        c.y -= c.w;
        clipDistance = -c.y;
    }
    return c;
}

// The hemicube frame around n, rotated about n by `angle` (HemicubeMath.cpp hemicubeFrame).
void hcFrame(vec3 n, float angle, out vec3 T, out vec3 B) {
    vec3 helper = abs(n.x) < 0.9 ? vec3(1.0, 0.0, 0.0) : vec3(0.0, 1.0, 0.0);
    vec3 t0 = normalize(cross(helper, n));
    vec3 b0 = cross(n, t0);
    T = cos(angle) * t0 + sin(angle) * b0;
    B = cross(T, n);
}

// The random per-position rotation (HemicubeMath.cpp rotationAngle, same hash).
float hcRotationAngle(vec3 p) {
    uint h = 2166136261u;
    for (int k = 0; k < 3; ++k) {
        uint q = uint(int(floor(p[k] * 1000.0)));
        h = (h ^ q) * 16777619u;
        h ^= h >> 15;
    }
    return float(h & 0xFFFFu) / 65536.0 * 6.28318530718;
}
