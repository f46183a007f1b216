// The one-pass refinement rule of Nichols 2010 §4.2.1.1 (checklist item 11): a cell of level k gathers
// iff a covered pixel lies below it, it is not refined at its level, and its parent is (or k is the
// coarsest level). stencil_setup.frag marks such cells in the atlas stencil; cell_list.comp lists them.
// Inputs: eye pyramid geometry and refine flags.
bool gathersHere(sampler2DArray geometry, sampler2DArray refineFlags, ivec2 cell, int level, int coarsest) {
    bool covered = texelFetch(geometry, ivec3(cell, 0), level).w > 0.0;
    bool ownRefine = level > 0 && texelFetch(refineFlags, ivec3(cell, 0), level).r > 0.5;
    ivec2 parentSize = textureSize(refineFlags, min(level + 1, coarsest)).xy;
    bool parentRefine = level == coarsest ||
                        texelFetch(refineFlags, ivec3(min(cell / 2, parentSize - 1), 0), level + 1).r > 0.5;
    return covered && !ownRefine && parentRefine;
}
