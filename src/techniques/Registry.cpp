#include "techniques/Registry.h"

#include "techniques/ambient/AmbientTechnique.h"
#include "techniques/direct/DirectTechnique.h"
#include "techniques/iir/IirTechnique.h"
#include "techniques/hisr/HisrTechnique.h"
#include "techniques/isr/IsrTechnique.h"
#include "techniques/multires_splat/MultiresSplatTechnique.h"
#include "techniques/rsm/RsmTechnique.h"
#include "techniques/photon_splat/PhotonSplatTechnique.h"
#include "techniques/area_light/AreaLightTechnique.h"
#include "techniques/radiosity_cross/CrossRadiosityTechnique.h"
#include "techniques/radiosity_gather/GatherRadiosityTechnique.h"
#include "techniques/radiosity_incremental/IncrementalRadiosityTechnique.h"
#include "techniques/radiosity_pr/ProgressiveRadiosityTechnique.h"
#include "techniques/rsm_splat/RsmSplatTechnique.h"
#include "techniques/vct/VctTechnique.h"

#include <fmt/ranges.h>

namespace bounce {

namespace {
// The reference scopes of docs/techniques/*.md.
constexpr ReferenceScope kDirectOnly{0, false, false, Component::Full};  // --bounces 0
constexpr ReferenceScope kEverything{-1, false, false, Component::Full};
constexpr ReferenceScope kOneBounce{1, true, false, Component::Indirect};  // --bounces 1 --indirect-only
constexpr ReferenceScope kOneDiffuseBounce{1, true, true, Component::Indirect};
constexpr ReferenceScope kDiffuseSolution{-1, false, true, Component::Full};  // radiosity: --diffuse-only
}  // namespace

const std::vector<TechniqueInfo>& registeredTechniques() {
    static const std::vector<TechniqueInfo> list = {
        {"direct", "direct light only (no indirect light)", "baseline", [] { return std::make_unique<DirectTechnique>(); }, kDirectOnly},
        {"ambient", "direct light plus a constant ambient term", "baseline", [] { return std::make_unique<AmbientTechnique>(); }, kEverything},
        {"iir", "incremental instant radiosity: incrementally maintained VPLs, paraboloid shadow maps, interleaved sampling",
         "Laine et al. 2007", [] { return std::make_unique<IirTechnique>(); }, kOneDiffuseBounce},
        {"rsm", "reflective shadow map: every pixel gathers every VPL (Nichols 2010 baseline)", "Nichols 2010 thesis; Dachsbacher & Stamminger 2005", [] { return std::make_unique<RsmTechnique>(); }, kOneBounce},
        {"rsm-splat", "reflective shadow map splatting: full-screen, fixed-radius or fragment-matched splats (Nichols 2010 baseline)", "Dachsbacher & Stamminger 2005; Nichols 2010 thesis fig. 4.8", [] { return std::make_unique<RsmSplatTechnique>(); }, kOneBounce},
        {"isr", "image-space radiosity: stencilled multiresolution gather, light-space VPL clusters (Nichols 2010 ch. 4)", "Nichols 2010 thesis ch. 4; Nichols, Shopf & Wyman 2009", [] { return std::make_unique<IsrTechnique>(); }, kOneBounce},
        {"multires-splat", "multiresolution splatting: subsplat refinement by geometry shader + transform feedback (Nichols 2010 ch. 3)", "Nichols 2010 thesis ch. 3; Nichols & Wyman, I3D 2009", [] { return std::make_unique<MultiresSplatTechnique>(); }, kOneBounce},
        {"vct", "voxel cone tracing: hybrid voxelization, isotropic / anisotropic / spherical-harmonics radiance, 60-degree cones (Rauwendaal 2013)",
         "Rauwendaal 2013 PhD thesis; Rauwendaal & Bailey, JCGT 2013", [] { return std::make_unique<VctTechnique>(); }, kOneBounce},
        {"photon-splat", "photon splatting: CPU-traced photons as orthographic bundles with their own depth maps, splatted as a calibrated flux estimate (the document's normalisation is a setting; seed 004)",
         "photon splatting with orthographic bundles (seed 004 thesis)", [] { return std::make_unique<PhotonSplatTechnique>(); }, kOneBounce},
        {"radiosity-gather", "hemicube gather radiosity: a radiosity hemicube per element per bounce, integrated with delta form factors (van de Hoef 2013 Alg. 4.1; the radiosity reference)",
         "van de Hoef 2013 MSc thesis; Cohen & Greenberg 1985", [] { return std::make_unique<GatherRadiosityTechnique>(); }, kDiffuseSolution},
        {"radiosity-pr", "GPU progressive refinement radiosity: shooter selection and subdivision, ID hemicubes, disk-approximation reconstruction (van de Hoef 2013 Alg. 4.2)",
         "van de Hoef 2013 MSc thesis; Cohen et al. 1988; Coombe et al. 2004", [] { return std::make_unique<ProgressiveRadiosityTechnique>(); }, kDiffuseSolution},
        {"radiosity-incremental", "incremental radiosity with reshooting: old/new ID hemicubes, negative shots, four visibility cases (van de Hoef 2013 Alg. 4.3)",
         "van de Hoef 2013 MSc thesis; Chen 1990; George et al. 1990", [] { return std::make_unique<IncrementalRadiosityTechnique>(); }, kDiffuseSolution},
        {"radiosity-cross", "cross redistribution radiosity: four hemicubes per moving patch, cross projection through back hemicubes (van de Hoef 2013 Alg. 4.4/4.5)",
         "van de Hoef 2013 MSc thesis", [] { return std::make_unique<CrossRadiosityTechnique>(); }, kDiffuseSolution},
        {"area-light", "multiresolution textured area lights: VPLs on the light texture, screen-space voxel visibility with incremental bitstreams, incremental stencil rendering (Nichols 2010 ch. 5; direct light only)",
         "Nichols 2010 thesis ch. 5; Nichols, Penmatsa & Wyman, UICS-10-01", [] { return std::make_unique<AreaLightTechnique>(); }, kDirectOnly},
        {"hisr", "hierarchical image-space radiosity: per-fragment VPL-tree traversal (Nichols 2010 ch. 4.2.4)", "Nichols 2010 thesis ch. 4; Nichols, Shopf & Wyman 2009", [] { return std::make_unique<HisrTechnique>(); }, kOneBounce},
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
