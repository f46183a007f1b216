// Rauwendaal 2013 sections 5.1.3 and 5.3.3: two-band SH in the thesis code's basis and the SH
// face-projection mipmap (Eq. 5.9), with the divide-by-pi normalisation of spec 2.9.
#include "techniques/vct/ShMath.h"

#include <glm/geometric.hpp>
#include <glm/gtc/constants.hpp>

#include <cmath>

namespace bounce::vct {

glm::vec4 shBasis(glm::vec3 d) { return glm::vec4(kShY00, -kShY1 * d.y, kShY1 * d.z, -kShY1 * d.x); }

float shEvaluate(glm::vec4 c, glm::vec3 d) { return glm::dot(c, shBasis(d)); }

glm::vec4 shCosineLobe(glm::vec3 d) {
    // Projection of max(0, d.w): band l of a clamped cosine is A_l Y_l(d) with A_0 = pi,
    // A_1 = 2 pi / 3 (Ramamoorthi & Hanrahan 2001; [Ins10]); pi Y00 = sqrt(pi)/2 and
    // (2 pi / 3) * sqrt(3) / (2 sqrt(pi)) = sqrt(pi/3).
    const float c0 = 0.5f * std::sqrt(glm::pi<float>());
    const float c1 = std::sqrt(glm::pi<float>() / 3.0f);
    return glm::vec4(c0, -c1 * d.y, c1 * d.z, -c1 * d.x);
}

glm::vec4 shProjectConstant(float L) { return glm::vec4(L / kShY00, 0.0f, 0.0f, 0.0f); }

double faceSolidAngleNumerical(bool nearFace, int samplesPerSide) {
    // The thesis's parametrisation (Eq. 5.2 and the back-face integral before it): x in [-1, 3],
    // y in [-3, 1], the face plane at distance h = 1 (near) or 3 (far); the integrand
    // <n_face, p> / |p| * 1 / |p|^2 is h / (x^2 + y^2 + h^2)^(3/2).
    const double h = nearFace ? 1.0 : 3.0;
    const double step = 4.0 / samplesPerSide;
    double sum = 0.0;
    for (int i = 0; i < samplesPerSide; ++i) {
        double x = -1.0 + (i + 0.5) * step;
        double row = 0.0;
        for (int j = 0; j < samplesPerSide; ++j) {
            double y = -3.0 + (j + 0.5) * step;
            double r2 = x * x + y * y + h * h;
            row += h / (r2 * std::sqrt(r2));
        }
        sum += row;
    }
    return sum * step * step;
}

glm::vec3 faceNormal(int face) {
    glm::vec3 n(0.0f);
    n[face / 2] = (face % 2 == 0) ? 1.0f : -1.0f;
    return n;
}

namespace {
glm::vec3 childCentre(int child) {
    return glm::vec3((child & 1) ? 1.0f : -1.0f, (child & 2) ? 1.0f : -1.0f, (child & 4) ? 1.0f : -1.0f);
}
}  // namespace

glm::vec3 childFaceDirection(int child, int face) {
    // Parent of edge 4 centred at the origin: face centre = 2 * faceNormal.
    return glm::normalize(2.0f * faceNormal(face) - childCentre(child));
}

bool isNearFace(int child, int face) {
    int axis = face / 2;
    bool positiveFace = face % 2 == 0;
    bool positiveChild = (child >> axis) & 1;
    return positiveFace == positiveChild;
}

glm::vec3 shEvaluateRgb(const ShRgb& c, glm::vec3 d) {
    glm::vec4 y = shBasis(d);
    return glm::vec3(glm::dot(c.r, y), glm::dot(c.g, y), glm::dot(c.b, y));
}

ShRgb shProjectConstantRgb(glm::vec3 radiance) {
    return ShRgb{shProjectConstant(radiance.r), shProjectConstant(radiance.g), shProjectConstant(radiance.b)};
}

ShRgb shMipParent(const std::array<std::optional<ShRgb>, 8>& children, bool divideByPi) {
    ShRgb sum;
    for (int i = 0; i < 8; ++i) {
        if (!children[i]) continue;
        const ShRgb& v = *children[i];
        for (int f = 0; f < 6; ++f) {
            glm::vec3 d = childFaceDirection(i, f);
            float omega = isNearFace(i, f) ? kShNearFaceSolidAngle : kShFarFaceSolidAngle;
            glm::vec4 y = shBasis(d);
            glm::vec4 lobe = shCosineLobe(d);
            sum.r += omega * glm::dot(y, v.r) * lobe;
            sum.g += omega * glm::dot(y, v.g) * lobe;
            sum.b += omega * glm::dot(y, v.b) * lobe;
        }
    }
    float scale = 1.0f / 8.0f;  // premultiplied: empty children count as zero
    if (divideByPi) scale /= glm::pi<float>();
    return ShRgb{sum.r * scale, sum.g * scale, sum.b * scale};
}

glm::mat4 shMipChildMatrix(int child) {
    glm::mat4 m(0.0f);
    for (int f = 0; f < 6; ++f) {
        const glm::vec3 d = childFaceDirection(child, f);
        const float omega = isNearFace(child, f) ? kShNearFaceSolidAngle : kShFarFaceSolidAngle;
        m += omega * glm::outerProduct(shCosineLobe(d), shBasis(d));
    }
    return m;
}

}  // namespace bounce::vct
