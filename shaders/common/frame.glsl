// Per-frame camera data for full-screen passes.
#include "common/shared.h"

layout(std140, binding = BINDING_UBO_FRAME) uniform FrameBlock { FrameUniforms u_frame; };
