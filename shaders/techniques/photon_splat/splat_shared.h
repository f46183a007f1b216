// Photon splatting (seed 004): one orthographic bundle as the splat passes see it (C++ and GLSL).
#ifndef BOUNCE_PHOTON_SPLAT_SHARED_H
#define BOUNCE_PHOTON_SPLAT_SHARED_H
#include "common/shared.h"
#ifdef __cplusplus
namespace bounce::gpu {
#endif

#define SPLAT_FILTER_BOX 0
#define SPLAT_FILTER_TENT 1
#define SPLAT_FILTER_GAUSSIAN 2

// Triangles per culling cluster (ClusterSet), also depth_raster.comp's workgroup size: one
// invocation per triangle of a (bundle, cluster) pair.
#define SPLAT_CLUSTER_TRIANGLES 32

#define SPLAT_ESTIMATE_NORMALIZED 0  // the document: sum(w S) / sum(w), times an exposure
#define SPLAT_ESTIMATE_FLUX 1        // bounce's calibrated mode: rho/pi sum Phi w_n cos V

// One bundle's volume (src/techniques/photon_splat/BundleVolume.h): local coordinates of x are
// (dot(x - P, right), dot(x - P, up), dot(x - P, w)); x is inside when |local.xy| <= h,
// farOffset <= dot(x, m) <= nearOffset and dot(x, n_P) >= emitterOffset. Its depth map covers local
// z in [zNear, zFar].
struct BundleGpu {
    vec4 origin;     // xyz: P (the photon), w: half size h (metres)
    vec4 direction;  // xyz: w (unit), w: length D (metres)
    vec4 right;      // xyz: unit axis of the cross-section, w: zNear (metres along w from P)
    vec4 up;         // xyz: unit axis, w: zFar
    vec4 nearPlane;  // xyz: m (unit, dot(w, m) < 0), w: nearOffset (metres)
    vec4 emitter;    // xyz: n_P (zero when unused), w: emitterOffset (metres; -1e30 when unused)
    vec4 power;      // rgb: photon power (W), w: unused
};

#ifdef __cplusplus
static_assert(sizeof(BundleGpu) == 112);
}  // namespace bounce::gpu
#endif
#endif
