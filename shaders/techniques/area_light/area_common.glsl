// Shared by the area-light passes (Nichols 2010 ch. 5): the pass uniforms, the VPLs and the culling
// tests of §5.3.2 that use the light's known position: a receiver that faces away from every corner
// of a light, or lies behind a one-sided light, gets nothing from it.
#include "techniques/area_light/area_shared.h"
#include "common/constants.glsl"
layout(std140, binding = BINDING_UBO_PASS) uniform AreaPassBlock { AreaPassUniforms u_pass; };

vec3 lightCorner(AreaLightGpu L, int k) {
    vec2 c = vec2(k & 1, k >> 1) - 0.5;
    return L.centre.xyz + c.x * L.edgeU.xyz + c.y * L.edgeV.xyz;
}

// True when no point of light L can light a receiver at x with normal n (§5.3.2's back-facing test
// over the corners, and the one-sided test).
bool culledByLight(AreaLightGpu L, vec3 x, vec3 n) {
    if (L.centre.w < 0.5 && dot(x - L.centre.xyz, L.normal.xyz) <= 0.0) return true;
    for (int k = 0; k < 4; ++k)
        if (dot(n, lightCorner(L, k) - x) > 0.0) return false;
    return true;
}

bool culledByAllLights(vec3 x, vec3 n) {
    for (int i = 0; i < int(u_pass.counts.x); ++i)
        if (!culledByLight(u_pass.lights[i], x, n)) return false;
    return true;
}

// x lies on the emitter of some light (its own G-buffer pixels): no gather there (§5.3.2, "emitter
// fragments are stenciled out").
bool onEmitter(vec3 x) {
    for (int i = 0; i < int(u_pass.counts.x); ++i) {
        AreaLightGpu L = u_pass.lights[i];
        vec3 d = x - L.centre.xyz;
        float size = max(L.edgeU.w, L.edgeV.w);
        if (abs(dot(d, L.normal.xyz)) > 1e-3 * size) continue;
        float u = dot(d, L.edgeU.xyz) / (L.edgeU.w * L.edgeU.w), v = dot(d, L.edgeV.xyz) / (L.edgeV.w * L.edgeV.w);
        if (abs(u) <= 0.5 + 1e-3 && abs(v) <= 0.5 + 1e-3) return true;
    }
    return false;
}

// Emission cosine at the light for direction -l (from the light towards the receiver): one-sided
// lights emit on the side of their normal, two-sided ones on both.
float emitterCosine(AreaLightGpu L, vec3 l) {
    float c = -dot(L.normal.xyz, l);
    return L.centre.w > 0.5 ? abs(c) : c;
}

// Where a visibility ray towards a point y on light L ends: u_pass.march.z metres off the emitter,
// along its normal on the receiver's side. Lights are usually mounted on a wall or ceiling, and a ray
// that ended on the emitter plane would run its last steps inside that surface's voxels (the origin
// bias of Fig. 5.12, applied at the light's end too; an assumption).
vec3 rayEnd(AreaLightGpu L, vec3 y, vec3 x) {
    float side = dot(x - y, L.normal.xyz) >= 0.0 ? 1.0 : -1.0;
    return y + side * u_pass.march.z * L.normal.xyz;
}

// 2x2 interleaved sampling (§5.3.3.2): the cell of parity s = (x & 1) + 2 (y & 1) at its level takes
// VPLs s, s + 4, s + 8, ...; one subset (interleave off) has parity 0 everywhere.
int alParity(ivec2 c, int subsets) { return subsets == 4 ? (c.x & 1) + 2 * (c.y & 1) : 0; }

// The "3x3 region" of §5.3.3.2 (reuse when "coarse samples in a 3x3 region agree"; the bit count over
// "a neighborhood") for one VPL subset: its samples lie on a lattice of spacing 2, so its 3x3 region
// around cell c is the subset's cells within 2 cells of c: 3 x 3 of them where c has that parity,
// 3 x 2 or 2 x 2 where c falls between them; without interleaving, the plain 3x3 block. The 3x3 block
// of cells holds only c itself of c's own parity, so an agreement over it was vacuous for a quarter
// of the children and a bit count over it never saw c's own subset (AreaLightGpuTest
// .IncrementalVisibilityFollowsTheThesissRules). Loop over the offsets in [-r, r]^2 and keep the
// cells of the subset's parity.
int alWindowRadius(int subsets) { return subsets == 4 ? 2 : 1; }

// The one scan of such regions (gather_diffuse.frag, gather_specular.frag, resolve.comp): offset i of
// the (2r + 1)^2 offsets in [-r, r]^2 around c, rows (dy) outer and columns (dx) inner, as
// `for (int i = 0; i < alRegionCells(r); ++i) { ivec2 q; if (!alRegionCell(c, r, size, i, q)) continue; ... }`.
// alRegionCell is false for a cell outside [0, size); alSubsetCell also for one not of parity s.
int alRegionCells(int r) { return (2 * r + 1) * (2 * r + 1); }
bool alRegionCell(ivec2 c, int r, ivec2 size, int i, out ivec2 q) {
    q = c + ivec2(i % (2 * r + 1), i / (2 * r + 1)) - ivec2(r);
    return all(greaterThanEqual(q, ivec2(0))) && all(lessThan(q, size));
}
bool alSubsetCell(ivec2 c, int r, ivec2 size, int subsets, int s, int i, out ivec2 q) {
    return alRegionCell(c, r, size, i, q) && alParity(q, subsets) == s;
}

// A subset's cells of a region must number at least this many before they can agree or disagree.
const int AL_MIN_REGION_SAMPLES = 2;

// Eq. 5.2's point form A cos_x cos_y / r^2 for a VPL of area A at distance r grows without bound as a
// receiver nears it; a patch of radiance L can give at most pi L cos_x cos_y (the receiver's whole
// hemisphere filled with it: the limit of the on-axis disk form factor A / (pi r^2 + A) as r -> 0).
// The squared distance the term divides by is therefore never below A / pi: the point form where
// r^2 >= A / pi (beyond 0.56 cell sides of a square cell), that bound nearer. The disk form itself,
// radiosity's A / (pi r^2 + A), is 6 % low still at 1.6 cell sides and 1.6 % at 3.2, where the point
// form is exact to 2e-4 (bench/area_light/nearfield.py); the clamp equals the point form from 0.8 cell
// sides on and bounds its spikes nearer (3.6x the exact irradiance at 0.32 cell sides: 1.24x).
float alNearFieldR2(float r2, float area) { return max(r2, area * kInvPi); }
