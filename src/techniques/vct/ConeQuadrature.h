#pragma once
// vct's six diffuse cones (Rauwendaal 2013 Eqs. 6.8-6.9, ConeSet.h) as the path tracer's first-reflection
// cone quadrature (PathTracerSettings::firstReflectionCones: `bounce reference --first-reflection
// vct-cones`, docs/techniques/vct.md "The six cones' own bias").
#include "reference/PathTracer.h"
#include "techniques/vct/ConeSet.h"

#include <vector>

namespace bounce::vct {

inline std::vector<PathTracerSettings::QuadratureCone> diffuseQuadratureCones() {
    std::vector<PathTracerSettings::QuadratureCone> cones;
    for (size_t k = 0; k < kDiffuseConeDirections.size(); ++k)
        cones.push_back({kDiffuseConeDirections[k], 0.5f * kDiffuseConeAperture, kDiffuseConeWeights[k]});
    return cones;
}

}  // namespace bounce::vct
