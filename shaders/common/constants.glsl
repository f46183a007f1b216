// Mathematical constants (no units).
#ifndef BOUNCE_CONSTANTS_GLSL
#define BOUNCE_CONSTANTS_GLSL
const float kPi = 3.14159265358979;
const float kInvPi = 0.318309886183791;
#endif
