#pragma once
// The registered techniques, one line each in Registry.cpp.
#include "techniques/Pipeline.h"
#include "techniques/Technique.h"

#include <functional>
#include <memory>
#include <vector>

namespace bounce {

// The ground truth a technique is compared with: `bounce reference --bounces K [--indirect-only]
// [--diffuse-only]` against the technique's output `component`. It is what the technique's doc page
// ("Reference scope") says it computes; `bounce sweep` compares with it unless a study overrides it.
struct ReferenceScope {
    int bounces = -1;  // indirect bounces K; -1 = unbounded (PathTracerSettings::kUnbounded)
    bool indirectOnly = false;
    bool diffuseOnly = false;
    Component component = Component::Full;
};

struct TechniqueInfo {
    std::string name;
    std::string summary;    // one line for `bounce list`
    std::string reference;  // paper or "baseline"
    std::function<std::unique_ptr<Technique>()> create;
    ReferenceScope scope;
};

const std::vector<TechniqueInfo>& registeredTechniques();
// Unknown names are an error listing the known ones.
Expected<std::unique_ptr<Technique>> createTechnique(std::string_view name);

}  // namespace bounce
