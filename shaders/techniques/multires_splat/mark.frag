// splatPrimitive=stencil, first pass: the refined subsplat list (splat.vert, one instance) marks its
// texels in the atlas stencil (ref 1, GL_REPLACE; colour writes off). Nothing to compute here.
void main() {}
