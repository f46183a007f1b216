// Rauwendaal 2013, section 4.1 (after Schwarz & Seidel 2010): the triangle/voxel overlap test with
// per-triangle factored constants, Figs. 4.4 (26-separating, "conservative") and 4.5 (6-separating,
// "thin"), and the dominant-axis swizzle of Eq. 4.1. Voxel space: unit voxels, voxel p spans
// [p, p + 1]; the grid is [0, N)^3. Mirrors src/techniques/vct/VoxelOverlap.cpp line for line (the
// unit tests check that code against a brute-force test; the GPU tests check this file against it).
// Errata applied (docs/techniques/vct.md): the printed listings test YZ and ZX with p.xy (here p.yz,
// p.zx); the conservative depth range is [floor(zlo), floor(zhi)], the thin one the voxel whose
// centre segment [k, k + 1) along the depth axis the plane crosses, k = floor(zc) for the plane's
// depth zc at the column centre (the printed floor/ceil pair would make every sheet two voxels thick).
#ifndef BOUNCE_VCT_OVERLAP_GLSL
#define BOUNCE_VCT_OVERLAP_GLSL

struct VoxTri {
    vec3 v0, v1, v2;   // swizzled so that XY is the plane of maximal projection
    int axis;          // dominant axis of the normal before the swizzle (0 x, 1 y, 2 z)
    vec3 n;            // sign(n.z) * n: the depth axis points away from the front
    vec2 nXY[3], nYZ[3], nZX[3];
    vec3 dXY, dYZ, dZX;
    float dA, dB;      // conservative: dmin, dmax; thin: dcen, unused
    ivec3 bmin, bmax;  // the triangle's voxel bounding box (swizzled), clamped to the grid
    bool valid;        // false for zero-area triangles and boxes outside the grid
};

// Eq. 4.1: xyz -> yzx when x dominates, zxy when y dominates.
vec3 voxSwizzle(vec3 v, int axis) { return axis == 0 ? v.yzx : (axis == 1 ? v.zxy : v); }
ivec3 voxUnswizzle(ivec3 p, int axis) { return axis == 0 ? p.zxy : (axis == 1 ? p.yzx : p); }
vec3 voxUnswizzleV(vec3 p, int axis) { return axis == 0 ? p.zxy : (axis == 1 ? p.yzx : p); }

int voxDominantAxis(vec3 n) {
    vec3 a = abs(n);
    if (a.x >= a.y && a.x >= a.z) return 0;
    return a.y >= a.z ? 1 : 2;
}

float voxSign(float x) { return x < 0.0 ? -1.0 : 1.0; }

VoxTri voxTriSetup(vec3 a, vec3 b, vec3 c, bool conservative, int N) {
    VoxTri t;
    vec3 nWorld = cross(b - a, c - a);
    t.valid = dot(nWorld, nWorld) > 1e-20;
    t.axis = voxDominantAxis(nWorld);
    t.v0 = voxSwizzle(a, t.axis);
    t.v1 = voxSwizzle(b, t.axis);
    t.v2 = voxSwizzle(c, t.axis);
    vec3 v[3] = vec3[3](t.v0, t.v1, t.v2);
    vec3 e[3] = vec3[3](t.v1 - t.v0, t.v2 - t.v1, t.v0 - t.v2);
    vec3 n = cross(e[0], e[1]);
    for (int i = 0; i < 3; ++i) {
        t.nXY[i] = voxSign(n.z) * vec2(-e[i].y, e[i].x);
        t.nYZ[i] = voxSign(n.x) * vec2(-e[i].z, e[i].y);
        t.nZX[i] = voxSign(n.y) * vec2(-e[i].x, e[i].z);
        if (conservative) {
            t.dXY[i] = -dot(t.nXY[i], v[i].xy) + max(0.0, t.nXY[i].x) + max(0.0, t.nXY[i].y);
            t.dYZ[i] = -dot(t.nYZ[i], v[i].yz) + max(0.0, t.nYZ[i].x) + max(0.0, t.nYZ[i].y);
            t.dZX[i] = -dot(t.nZX[i], v[i].zx) + max(0.0, t.nZX[i].x) + max(0.0, t.nZX[i].y);
        } else {
            t.dXY[i] = dot(t.nXY[i], vec2(0.5) - v[i].xy) + 0.5 * max(abs(t.nXY[i].x), abs(t.nXY[i].y));
            t.dYZ[i] = dot(t.nYZ[i], vec2(0.5) - v[i].yz) + 0.5 * max(abs(t.nYZ[i].x), abs(t.nYZ[i].y));
            t.dZX[i] = dot(t.nZX[i], vec2(0.5) - v[i].zx) + 0.5 * max(abs(t.nZX[i].x), abs(t.nZX[i].y));
        }
    }
    n *= voxSign(n.z);
    t.n = n;
    if (conservative) {
        t.dA = dot(n, t.v0) - max(0.0, n.x) - max(0.0, n.y);
        t.dB = dot(n, t.v0) - min(0.0, n.x) - min(0.0, n.y);
    } else {
        t.dA = dot(n, t.v0) - 0.5 * n.x - 0.5 * n.y;
        t.dB = 0.0;
    }
    vec3 lo = min(t.v0, min(t.v1, t.v2)), hi = max(t.v0, max(t.v1, t.v2));
    t.bmin = max(ivec3(floor(lo)), ivec3(0));
    t.bmax = min(ivec3(floor(hi)), ivec3(N - 1));
    if (any(greaterThan(t.bmin, t.bmax))) t.valid = false;
    return t;
}

bool voxTestXY(VoxTri t, vec2 p) {
    return dot(t.nXY[0], p) + t.dXY[0] >= 0.0 && dot(t.nXY[1], p) + t.dXY[1] >= 0.0 &&
           dot(t.nXY[2], p) + t.dXY[2] >= 0.0;
}

bool voxTestYZZX(VoxTri t, vec3 p) {
    return dot(t.nYZ[0], p.yz) + t.dYZ[0] >= 0.0 && dot(t.nYZ[1], p.yz) + t.dYZ[1] >= 0.0 &&
           dot(t.nYZ[2], p.yz) + t.dYZ[2] >= 0.0 && dot(t.nZX[0], p.zx) + t.dZX[0] >= 0.0 &&
           dot(t.nZX[1], p.zx) + t.dZX[1] >= 0.0 && dot(t.nZX[2], p.zx) + t.dZX[2] >= 0.0;
}

// The voxels along the depth axis of column p.xy the plane test leaves (inclusive range).
ivec2 voxDepthRange(VoxTri t, vec2 p, bool conservative) {
    float base = -dot(t.n.xy, p);
    int zmin, zmax;
    if (conservative) {
        zmin = int(floor((base + t.dA) / t.n.z));
        zmax = int(floor((base + t.dB) / t.n.z));
    } else {
        float zc = (base + t.dA) / t.n.z;
        zmin = int(floor(zc));
        zmax = zmin;
    }
    return ivec2(max(zmin, t.bmin.z), min(zmax, t.bmax.z));
}

#endif
