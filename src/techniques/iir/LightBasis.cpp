#include "techniques/iir/LightBasis.h"

#include "core/Check.h"

#include <glm/geometric.hpp>

#include <cmath>

namespace bounce {

LightBasis LightBasis::fromAxis(const glm::dvec3& axisIn) {
    const double length = glm::length(axisIn);
    BOUNCE_CHECK(length > 0.0 && std::isfinite(length), "light axis ({}, {}, {}) has no direction", axisIn.x,
                 axisIn.y, axisIn.z);
    const glm::dvec3 n = axisIn / length;
    const double sign = std::copysign(1.0, n.z);
    const double a = -1.0 / (sign + n.z);
    const double b = n.x * n.y * a;
    LightBasis basis;
    basis.tangent = glm::dvec3(1.0 + sign * n.x * n.x * a, sign * b, -sign * n.x);
    basis.bitangent = glm::dvec3(b, sign + n.y * n.y * a, -n.y);
    basis.axis = n;
    return basis;
}

glm::dvec3 LightBasis::toLocal(const glm::dvec3& world) const {
    return glm::dvec3(glm::dot(world, tangent), glm::dot(world, bitangent), glm::dot(world, axis));
}

glm::dvec3 LightBasis::toWorld(const glm::dvec3& local) const {
    return local.x * tangent + local.y * bitangent + local.z * axis;
}

}  // namespace bounce
