#include "techniques/Registry.h"

#include "techniques/ambient/AmbientTechnique.h"
#include "techniques/direct/DirectTechnique.h"
#include "techniques/iir/IirTechnique.h"

#include <fmt/ranges.h>

namespace bounce {

const std::vector<TechniqueInfo>& registeredTechniques() {
    static const std::vector<TechniqueInfo> list = {
        {"direct", "direct light only (no indirect light)", "baseline", [] { return std::make_unique<DirectTechnique>(); }},
        {"ambient", "direct light plus a constant ambient term", "baseline", [] { return std::make_unique<AmbientTechnique>(); }},
        {"iir", "incremental instant radiosity: incrementally maintained VPLs, paraboloid shadow maps, interleaved sampling",
         "Laine et al. 2007", [] { return std::make_unique<IirTechnique>(); }},
    };
    return list;
}

Expected<std::unique_ptr<Technique>> createTechnique(std::string_view name) {
    std::vector<std::string> names;
    for (const TechniqueInfo& t : registeredTechniques()) {
        if (t.name == name) return t.create();
        names.push_back(t.name);
    }
    return makeError("unknown technique '{}' (known: {})", name, fmt::join(names, ", "));
}

}  // namespace bounce
