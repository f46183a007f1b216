// Rauwendaal 2013 section 5.1.3 / 5.3.3: 2-band spherical harmonics in the thesis code's basis
// (Fig. B.3), coefficient order (Y00, Y1-1, Y10, Y11) with Condon-Shortley signs (Table 2.1).
// Mirrors src/techniques/vct/ShMath.cpp.
#ifndef BOUNCE_VCT_SH_GLSL
#define BOUNCE_VCT_SH_GLSL

const float kShY00 = 0.2820947918;  // 1 / (2 sqrt(pi))
const float kShY1 = 0.488602512;    // sqrt(3) / (2 sqrt(pi))
// Subtended solid angles of a parent face seen from a child centre (Eqs. 5.2-5.4 with the erratum
// of the spec: the near face, coplanar with the child's outer face, is the wide one).
const float kShNearFaceSolidAngle = 3.113997196;  // sr
const float kShFarFaceSolidAngle = 1.074793009;   // sr

vec4 shBasis(vec3 d) { return vec4(kShY00, -kShY1 * d.y, kShY1 * d.z, -kShY1 * d.x); }
// Clamped cosine lobe around d (Eq. 5.8): (sqrt(pi)/2, -sqrt(pi/3) y, sqrt(pi/3) z, -sqrt(pi/3) x).
vec4 shCosineLobe(vec3 d) { return vec4(0.8862269255, -1.0233267079 * d.y, 1.0233267079 * d.z, -1.0233267079 * d.x); }

#endif
