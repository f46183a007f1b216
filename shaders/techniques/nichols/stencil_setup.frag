// One-pass multiresolution stencil set-up (Nichols 2010 §4.2.1.1, checklist item 11), drawn over each
// level's rectangle of the flattened atlas with stencil op REPLACE: a fragment survives iff its cell
// is covered, has no refinement at its own level (the finest level always qualifies) and its parent
// is refined (the coarsest level always qualifies). Because refine() is monotone (pyramid_flag.comp),
// every covered pixel is marked at exactly one level.
// Host uniforms: u_level, u_levelOrigin, u_coarsest (index of the coarsest level).
// Inputs: eye pyramid geometry and refine (BINDING_TEX_TECH0, TECH1). Output: stencil only.
#include "techniques/nichols/atlas.glsl"
layout(binding = BINDING_TEX_TECH0) uniform sampler2DArray s_geometry;
layout(binding = BINDING_TEX_TECH1) uniform sampler2DArray s_refine;
uniform int u_coarsest;

void main() {
    ivec2 cell = ivec2(gl_FragCoord.xy) - u_levelOrigin;
    bool covered = texelFetch(s_geometry, ivec3(cell, 0), u_level).w > 0.0;
    bool ownRefine = u_level > 0 && texelFetch(s_refine, ivec3(cell, 0), u_level).r > 0.5;
    ivec2 parentSize = textureSize(s_refine, min(u_level + 1, u_coarsest)).xy;
    bool parentRefine = u_level == u_coarsest || texelFetch(s_refine, ivec3(min(cell / 2, parentSize - 1), 0), u_level + 1).r > 0.5;
    if (!covered || ownRefine || !parentRefine) discard;
}
