// Incremental stencil rendering, the per-level classification (Nichols 2010 §5.3.4, checklist item
// 22; the pseudo-code of §2.3.6 in the summary), run coarsest level first. A cell of level k is
//   in the tree   when it is covered, not culled, and (k is the coarsest level, or its parent is in the
//                 tree and was refined by depth/normal(/lobe) or lit discontinuously);
//   rendered      when in the tree and (its parent was lit discontinuously: "SetStencil; continue",
//                 or it needs no depth/normal(/lobe) refinement itself, or it is the finest level).
// Tree cells that are not rendered still compute visibility: their bitstreams seed the 3x3 reuse
// of their children (§5.3.3.2). Culling (§5.3.2): emitter cells, cells facing away from every corner
// of every light or behind one-sided lights; the specular pass also culls cells without specular
// pixels and cells whose lobe misses every light (§5.3.2.1). A cell is culled only when it needs no
// refinement (a mixed cell's mean normal says nothing; its children decide).
// The specular pass adds the lobe refinement metric: the reflection direction varies across a cell
// by about its angular size seen from the eye plus twice its normal spread; when that exceeds the
// lobe's half-angle the sample spacing is coarser than the lobe and the cell is refined. A material
// boundary (specular and diffuse pixels, or roughness spread > kRoughnessSpread) refines too.
// Host uniforms: u_level, u_levelOrigin, u_parentOrigin, u_coarsest, u_specular.
// Inputs: eye pyramid geometry, refine, normal, lobe (BINDING_TEX_TECH0..3), normalMin/Max
// (BINDING_TEX_INPUT0/1), u_frame, u_pass. In/out: cell flags (image BINDING_IMG0, r32ui atlas).
#include "techniques/area_light/area_common.glsl"
#include "techniques/area_light/lobe.glsl"
#include "common/frame.glsl"
layout(local_size_x = 8, local_size_y = 8) in;
layout(binding = BINDING_TEX_TECH0) uniform sampler2DArray s_geometry;
layout(binding = BINDING_TEX_TECH1) uniform sampler2DArray s_refine;
layout(binding = BINDING_TEX_TECH2) uniform sampler2DArray s_normal;
layout(binding = BINDING_TEX_TECH3) uniform sampler2DArray s_lobe;
layout(binding = BINDING_TEX_INPUT0) uniform sampler2DArray s_normalMin;
layout(binding = BINDING_TEX_INPUT1) uniform sampler2DArray s_normalMax;
layout(r32ui, binding = BINDING_IMG0) uniform uimage2D i_flags;
uniform int u_level;
uniform ivec2 u_levelOrigin;
uniform ivec2 u_parentOrigin;
uniform int u_coarsest;
uniform bool u_specular;

const float kRoughnessSpread = 0.1;  // roughness range inside a cell that counts as a material edge (assumption)

bool geometryRefines(ivec2 c, int level, out bool specularCulled) {
    specularCulled = false;
    bool refine = level > 0 && texelFetch(s_refine, ivec3(c, 0), level).r > 0.5;
    if (!u_specular) return refine;
    vec4 lobe = texelFetch(s_lobe, ivec3(c, 0), level);
    if (lobe.z < 0.5) {  // no specular pixel below: nothing for this pass
        specularCulled = true;
        return refine;
    }
    if (level == 0) return false;
    if (lobe.w > 0.5 || lobe.y - lobe.x > kRoughnessSpread) return true;
    vec3 nMin = texelFetch(s_normalMin, ivec3(c, 0), level).xyz, nMax = texelFetch(s_normalMax, ivec3(c, 0), level).xyz;
    float spread = float(1 << level) * u_pass.lobe.w + 2.0 * max(max(nMax.x - nMin.x, nMax.y - nMin.y), nMax.z - nMin.z);
    return refine || spread > lobeHalfAngle(lobe.x, u_pass.lobe.x) * u_pass.lobe.z;
}

void main() {
    ivec2 c = ivec2(gl_GlobalInvocationID.xy);
    ivec2 size = textureSize(s_geometry, u_level).xy;
    if (any(greaterThanEqual(c, size))) return;
    uint flags = 0u;
    vec4 g = texelFetch(s_geometry, ivec3(c, 0), u_level);
    if (g.w > 0.0) {
        bool specularCulled;
        bool refine = geometryRefines(c, u_level, specularCulled);
        bool parentTree = true, parentLitRefine = false;
        if (u_level < u_coarsest) {
            ivec2 parentSize = textureSize(s_geometry, u_level + 1).xy;
            ivec2 p = min(c / 2, parentSize - 1);
            uint pf = imageLoad(i_flags, u_parentOrigin + p).r;
            bool dummy;
            bool parentRefine = geometryRefines(p, u_level + 1, dummy);
            parentLitRefine = (pf & AL_CELL_REFINE) != 0u;
            parentTree = (pf & AL_CELL_TREE) != 0u && (parentRefine || parentLitRefine);
        }
        vec3 x = g.xyz / g.w;
        vec3 n = normalize(texelFetch(s_normal, ivec3(c, 0), u_level).xyz + vec3(0.0, 0.0, 1e-12));
        bool culled = specularCulled || onEmitter(x) || culledByAllLights(x, n);
        if (!culled && u_specular) {
            vec4 lobe = texelFetch(s_lobe, ivec3(c, 0), u_level);
            vec3 R = reflect(-normalize(u_frame.eyePosition.xyz - x), n);
            float cosLobe = cos(lobeHalfAngle(lobe.x, u_pass.lobe.x));
            culled = true;
            for (int i = 0; i < int(u_pass.counts.x); ++i)
                if (!lobeMissesLight(u_pass.lights[i], x, R, cosLobe)) culled = false;
        }
        if (parentTree && !(culled && !refine)) {
            flags = AL_CELL_TREE;
            if (parentLitRefine || !refine) flags |= AL_CELL_RENDERED;
        }
    }
    imageStore(i_flags, u_levelOrigin + c, uvec4(flags));
}
