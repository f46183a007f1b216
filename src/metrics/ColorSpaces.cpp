#include "metrics/ColorSpaces.h"

#include <glm/mat3x3.hpp>
#include <glm/matrix.hpp>

#include <cmath>

namespace bounce {
namespace {

// IEC 61966-2-1 (sRGB) primaries and D65 white point, CIE 1931 xy chromaticities.
constexpr double kRedX = 0.64, kRedY = 0.33;
constexpr double kGreenX = 0.30, kGreenY = 0.60;
constexpr double kBlueX = 0.15, kBlueY = 0.06;
constexpr double kWhiteX = 0.3127, kWhiteY = 0.3290;

glm::dvec3 xyToXyz(double x, double y) { return {x / y, 1.0, (1.0 - x - y) / y}; }

// The RGB -> XYZ matrix whose columns are the primaries scaled so that RGB (1,1,1) maps to the
// white point with Y = 1 (the standard derivation, e.g. Poynton, "Digital Video and HD", ch. 26).
struct RgbXyzMatrices {
    glm::mat3 rgbToXyz;
    glm::mat3 xyzToRgb;
    glm::vec3 white;
    RgbXyzMatrices() {
        const glm::dmat3 primaries(xyToXyz(kRedX, kRedY), xyToXyz(kGreenX, kGreenY), xyToXyz(kBlueX, kBlueY));
        const glm::dvec3 whiteXyz = xyToXyz(kWhiteX, kWhiteY);
        const glm::dvec3 scale = glm::inverse(primaries) * whiteXyz;
        glm::dmat3 m = primaries;
        for (int c = 0; c < 3; ++c) m[c] *= scale[c];
        rgbToXyz = glm::mat3(m);
        xyzToRgb = glm::mat3(glm::inverse(m));
        white = glm::vec3(m * glm::dvec3(1.0));
    }
};

const RgbXyzMatrices& matrices() {
    static const RgbXyzMatrices kMatrices;
    return kMatrices;
}

// CIELAB companding: t^(1/3) above delta^3, a line of matching value and slope below.
constexpr double kLabDelta = 6.0 / 29.0;

float labForward(float t) {
    constexpr double kDelta3 = kLabDelta * kLabDelta * kLabDelta;
    return t > kDelta3 ? std::cbrt(t) : static_cast<float>(t / (3.0 * kLabDelta * kLabDelta) + 4.0 / 29.0);
}

float labInverse(float f) {
    return f > kLabDelta ? f * f * f : static_cast<float>(3.0 * kLabDelta * kLabDelta * (f - 4.0 / 29.0));
}

}  // namespace

glm::vec3 referenceWhiteXyz() { return matrices().white; }

glm::vec3 linearRgbToXyz(glm::vec3 rgb) { return matrices().rgbToXyz * rgb; }
glm::vec3 xyzToLinearRgb(glm::vec3 xyz) { return matrices().xyzToRgb * xyz; }

glm::vec3 xyzToCielab(glm::vec3 xyz) {
    const glm::vec3 n = xyz / referenceWhiteXyz();
    const float fx = labForward(n.x), fy = labForward(n.y), fz = labForward(n.z);
    return {116.0f * fy - 16.0f, 500.0f * (fx - fy), 200.0f * (fy - fz)};
}

glm::vec3 cielabToXyz(glm::vec3 lab) {
    const float fy = (lab.x + 16.0f) / 116.0f;
    const float fx = fy + lab.y / 500.0f;
    const float fz = fy - lab.z / 200.0f;
    return glm::vec3(labInverse(fx), labInverse(fy), labInverse(fz)) * referenceWhiteXyz();
}

glm::vec3 xyzToYcxcz(glm::vec3 xyz) {
    const glm::vec3 n = xyz / referenceWhiteXyz();
    return {116.0f * n.y - 16.0f, 500.0f * (n.x - n.y), 200.0f * (n.y - n.z)};
}

glm::vec3 ycxczToXyz(glm::vec3 ycxcz) {
    const float y = (ycxcz.x + 16.0f) / 116.0f;
    const float x = y + ycxcz.y / 500.0f;
    const float z = y - ycxcz.z / 200.0f;
    return glm::vec3(x, y, z) * referenceWhiteXyz();
}

}  // namespace bounce
