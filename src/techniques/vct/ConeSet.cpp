// Rauwendaal 2013 sections 6.1-6.4: cone ratio, start distance and voxel extent.
#include "techniques/vct/ConeSet.h"

#include <glm/geometric.hpp>

#include <cmath>

namespace bounce::vct {

float coneRatio(float apertureRadians) {
    float s = std::sin(0.5f * apertureRadians);
    return s / (1.0f - s);
}

float coneStartDistance(float nDotOmega, float voxelExtentValue, float fMin, float fMax) {
    // max() first: n . w below fMin / fMax gives exactly fMax |v| and never divides by <= 0.
    float lo = fMin * voxelExtentValue, hi = fMax * voxelExtentValue;
    float d = lo / std::fmax(nDotOmega, fMin / fMax);
    return d < lo ? lo : (d > hi ? hi : d);
}

float voxelExtent(Separability s, glm::vec3 voxelSize) {
    if (s == Separability::Conservative26) return glm::length(voxelSize);
    return std::fmax(voxelSize.x, std::fmax(voxelSize.y, voxelSize.z));
}

}  // namespace bounce::vct
