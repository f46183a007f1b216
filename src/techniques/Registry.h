#pragma once
// The registered techniques, one line each in Registry.cpp.
#include "techniques/Technique.h"

#include <functional>
#include <memory>
#include <vector>

namespace bounce {

struct TechniqueInfo {
    std::string name;
    std::string summary;    // one line for `bounce list`
    std::string reference;  // paper or "baseline"
    std::function<std::unique_ptr<Technique>()> create;
};

const std::vector<TechniqueInfo>& registeredTechniques();
// Unknown names are an error listing the known ones.
Expected<std::unique_ptr<Technique>> createTechnique(std::string_view name);

}  // namespace bounce
