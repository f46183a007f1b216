// isr's gather over the cell list (gatherPass=compute; techniques/nichols/cell_gather.glsl): the same
// cells and sums as the stencilled draw (isr/gather.frag), one invocation per listed cell.
#include "techniques/isr/gather.glsl"
#include "techniques/nichols/cell_gather.glsl"
