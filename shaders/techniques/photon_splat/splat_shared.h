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

#define SPLAT_ESTIMATE_NORMALIZED 0  // the document: sum(w S) / sum(w), times an exposure
#define SPLAT_ESTIMATE_FLUX 1        // bounce's calibrated mode: rho/pi sum Phi w_n cos V

struct BundleGpu {
    vec4 origin;     // xyz: C (the frustum's near-plane centre), w: half size h (metres)
    vec4 direction;  // xyz: w (unit), w: depth D (metres)
    vec4 right;      // xyz: unit axis of the cross-section, w: step back b (metres)
    vec4 up;         // xyz: unit axis, w: unused
    vec4 power;      // rgb: photon power (W), w: unused
};

#ifdef __cplusplus
static_assert(sizeof(BundleGpu) == 80);
}  // namespace bounce::gpu
#endif
#endif
