// One-pass multiresolution stencil set-up (Nichols 2010 §4.2.1.1, checklist item 11), drawn over each
// level's rectangle of the flattened atlas with stencil op REPLACE: a fragment survives iff its cell
// is covered, has no refinement at its own level (the finest level always qualifies) and its parent
// is refined (the coarsest level always qualifies). Because refine() is monotone (pyramid_flag.comp),
// every covered pixel is marked at exactly one level.
// Host uniforms: u_level, u_levelOrigin, u_coarsest (index of the coarsest level).
// Inputs: eye pyramid geometry and refine (BINDING_TEX_TECH0, TECH1). Output: stencil only.
#include "techniques/nichols/atlas.glsl"
#include "techniques/nichols/stencil_rule.glsl"
layout(binding = BINDING_TEX_TECH0) uniform sampler2DArray s_geometry;
layout(binding = BINDING_TEX_TECH1) uniform sampler2DArray s_refine;
uniform int u_coarsest;

void main() {
    if (!gathersHere(s_geometry, s_refine, ivec2(gl_FragCoord.xy) - u_levelOrigin, u_level, u_coarsest)) discard;
}
