// hisr's gather over the cell list (gatherPass=compute; techniques/nichols/cell_gather.glsl): the same
// cells and walks as the stencilled draw (hisr/gather.frag), one invocation per listed cell.
#include "techniques/hisr/gather.glsl"
#include "techniques/nichols/cell_gather.glsl"
