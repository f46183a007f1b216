// Incremental stencil rendering (Nichols 2010 §5.3.4): level k's stencil from the flags classify.comp
// just wrote, drawn over the level's rectangle of the atlas with stencil op REPLACE. u_ref 1 keeps the
// rendered cells (gather and shade), u_ref 2 the tree cells that only compute visibility.
// Host uniforms: u_level, u_levelOrigin, u_ref. Inputs: cell flags (BINDING_TEX_TECH0, r32ui atlas).
#include "techniques/nichols/atlas.glsl"
#include "techniques/area_light/area_shared.h"
layout(binding = BINDING_TEX_TECH0) uniform usampler2D s_flags;
uniform int u_ref;

void main() {
    uint f = texelFetch(s_flags, ivec2(gl_FragCoord.xy), 0).r;
    bool rendered = (f & AL_CELL_RENDERED) != 0u, tree = (f & AL_CELL_TREE) != 0u;
    if (u_ref == 1 ? !rendered : !(tree && !rendered)) discard;
}
