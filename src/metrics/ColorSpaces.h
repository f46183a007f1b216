#pragma once
// Colour-space conversions used by FLIP and the heat-map colour map: linear sRGB (Rec. 709
// primaries, D65) <-> CIE XYZ <-> CIELAB, and the YCxCz opponent space of FLIP (Andersson et al.
// 2020, after Zhang & Wandell's S-CIELAB). The reference white everywhere is XYZ of linear RGB
// (1, 1, 1), so white is L* = 100, a* = b* = 0 exactly.
#include <glm/vec3.hpp>

namespace bounce {

glm::vec3 linearRgbToXyz(glm::vec3 rgb);
glm::vec3 xyzToLinearRgb(glm::vec3 xyz);

// CIE 1976 L*a*b* (CIE 15:2004 formulas, with the linear segment below (6/29)^3).
glm::vec3 xyzToCielab(glm::vec3 xyz);
glm::vec3 cielabToXyz(glm::vec3 lab);

// YCxCz: Y = 116 Y/Yn - 16, Cx = 500 (X/Xn - Y/Yn), Cz = 200 (Y/Yn - Z/Zn). Affine in XYZ, so it
// commutes with normalised linear filters (which is why FLIP filters in this space).
glm::vec3 xyzToYcxcz(glm::vec3 xyz);
glm::vec3 ycxczToXyz(glm::vec3 ycxcz);

// XYZ of the reference white (linear RGB (1, 1, 1)).
glm::vec3 referenceWhiteXyz();

}  // namespace bounce
