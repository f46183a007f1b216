// The flattened multiresolution illumination buffer (Nichols 2010 §4.2.1.1; the layout diagram is
// lost, this one is an assumption): level 0 (W x H) at the origin, levels k >= 1 stacked in a column
// to its right starting at x = W, y = sum of the heights of levels 1..k-1. Atlas size (W + W/2) x H.
// Host uniforms: u_levelOrigin (atlas texel of the level's (0,0)), u_level.
uniform ivec2 u_levelOrigin;
uniform int u_level;
