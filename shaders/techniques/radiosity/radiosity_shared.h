// Dynamic hemicube radiosity (van de Hoef 2013): the records shared by C++ and GLSL. Members are
// vec4/uvec4/mat4 only, so std430 = C++ layout (static_asserts in RadiositySystem.cpp).
//
// Radiometry: what the thesis calls radiosity B (W/m^2) is stored divided by pi, i.e. as the exitant
// radiance of a Lambertian element, W/(m^2 sr). Every equation of the thesis is linear in B, so
// B_i = E_i + rho_i sum_j F_ij B_j holds unchanged for B/pi and E/pi, and the display samples the
// stored value directly as radiance. "B", "unshot", "shot", "total" below are such radiances.
#ifndef BOUNCE_RADIOSITY_SHARED_H
#define BOUNCE_RADIOSITY_SHARED_H

#include "common/shared.h"

#ifdef __cplusplus
namespace bounce::gpu {
#endif

#define RAD_QUAD_EMITTER 1u  // flags
#define RAD_QUAD_LIGHT 2u    // an area light's rectangle (not scene geometry; drawn by the radiosity passes)
#define RAD_NO_QUAD 0xFFFFFFFFu

// Receivers of a reconstruction pass (RadPassUniforms::modes.y).
#define RAD_RECEIVERS_ALL 0
#define RAD_RECEIVERS_STATIC 1   // C: quads of bodies that did not move
#define RAD_RECEIVERS_MOVING 2   // M: quads of bodies that moved

// Reconstruction kinds (RadPassUniforms::modes.x).
#define RAD_SHOOT_UNSHOT 0       // Alg. 4.2 RECONSTRUCTIONSHADER(s, e, unshot)
#define RAD_SHOOT_TOTAL 1        // ... (s, e, total) (Alg. 4.3 line 13, Alg. 4.4 line 15)
#define RAD_SHOOT_NEG_SHOT 2     // ... (s, e, -shot) with the old hemicube (Alg. 4.3 line 3)
#define RAD_SHOOT_INCREMENTAL 3  // INCREMENTALRECONSTRUCTIONSHADER (Alg. 4.3)
#define RAD_SHOOT_CROSS 4        // CROSSPROJECTIONRECONSTRUCTIONSHADER (Alg. 4.5)

// PROJECTEDRADIOSITY options (RadPassUniforms::slots.w, bits).
#define RAD_CROSS_REPROJECT 1u     // REPROJECT the rays with the back distance hemicube (sec. 4.5.2)
#define RAD_CROSS_FF_WEIGHTS 2u    // weight the rays by their form factor, not their area (bounce's option)

#define RAD_MAX_BATCH 16         // shooters per reconstruction pass (thesis benchmarks: 10)

// One chart of the scene (a rectangle on which connected, near-coplanar triangles of one object are
// parametrized: PatchModel.h) or an area light, owning an nu x nv texel region of the radiosity atlas
// whose outer texel ring lies on the rectangle's edges (thesis Fig. 4.1.2).
struct RadQuadGpu {
    vec4 p0, p1, p2, p3;  // object-space rectangle corners at (s,t) = (0,0) (1,0) (1,1) (0,1); w: unused
    vec4 normal;          // object-space unit normal (front side); w: area the chart covers, m^2
    vec4 emission;        // rgb: emitted radiance E, W/(m^2 sr); w: unused
    uvec4 atlas;          // x, y: texel offset of the region; z: nu; w: nv (>= 2 each)
    uvec4 info;           // x: body; y: first element; z: RAD_QUAD_* flags; w: surface (what ID hemicubes hold)
};

// One element = one atlas texel (a receiver).
struct RadElementGpu {
    vec4 position;  // object-space sample position (the covered part's centroid); w: area, m^2 (0 for ghosts)
    vec4 albedo;    // rgb: rho
    vec4 emission;  // rgb: E, W/(m^2 sr)
    uvec4 info;     // x: quad; y: atlas texel x | y << 16; z: body; w: i | j << 16 within the quad
};

// A shooting patch: a rectangle of a quad's elements (intermediate texture T of Alg. 4.2).
struct RadShooterGpu {
    vec4 position;  // object-space area-weighted centre; w: area A_s, m^2
    vec4 normal;    // object-space normal
    vec4 rect;      // (s0, t0, s1, t1): the patch's extent in the quad's parameter square
    vec4 unshot;    // area-weighted mean unshot radiance (what RAD_SHOOT_UNSHOT shoots)
    vec4 shot;      // area-weighted mean shot radiance B - Bu (what RAD_SHOOT_NEG_SHOT negates)
    vec4 total;     // area-weighted mean total radiance B
    uvec4 range;    // element rectangle [x, z] x [y, w] (inclusive) within the quad
    uvec4 info;     // x: quad; y: body; z: RAD_QUAD_* flags of the quad; w: unused
};

// A hemicube: origin and frame. The five faces are rendered into layers 5k .. 5k+4 of one array
// (face 0 the top, R x R; faces 1-4 the sides in rows [0, R/2)). Face f looks along axis A_f with
// up U_f and right cross(A_f, U_f): (N, B), (T, N), (-T, N), (B, N), (-B, N), B = cross(T, N).
struct RadHemicubeGpu {
    vec4 origin;   // world position; w: near plane, metres
    vec4 tangent;  // T (rotated about N by a hash of the origin when randomRotation is on)
    vec4 bitangent;
    vec4 normal;   // N: the hemicube's axis (the back hemicubes of Alg. 4.4 use -N of the patch)
    uvec4 info;    // x: element (gather) or shooter index; y: 1 if placed with the old bodies
};

// A body: a scene object, or an area light's rectangle (after the objects).
struct RadBodyGpu {
    mat4 worldFromObject;
    mat4 normalFromObject;
    uvec4 info;  // x: 1 if it moved since the last redistribution; y: 1 if animated at all
};

struct RadPassUniforms {
    uvec4 modes;   // x: RAD_SHOOT_*; y: RAD_RECEIVERS_*; z: shooter count in the batch; w: visibility samples (1 or 4)
    uvec4 counts;  // x: elements; y: hemicube face size R; z: back face size; w: cross grid size
    uvec4 slots;   // x: first shooter; y: first hemicube record; z: use old bodies for receivers; w: RAD_CROSS_* bits
    vec4 params;   // x: form-factor subdivision ratio A/r^2; y: sub-disks per side; z: msaa samples; w: 1 = insert M (no old terms)
};

#ifdef __cplusplus
}  // namespace bounce::gpu
#endif

#endif
