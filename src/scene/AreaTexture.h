#pragma once
// Evaluating an area light's emission texture (Scene.h, AreaTexture) at a time: which image a sequence
// shows, the bouncing-square test pattern rasterised, and the mean multiplier (the factor the light's
// flux and an untextured renderer's uniform radiance take). GL-free: the reference, the GPU light set
// and the area-light technique all read the texture through these functions, so they agree on the
// frame shown at time t.
#include "core/Error.h"
#include "scene/Scene.h"

#include <string>

namespace bounce {

// Largest procedural area-light texture, texels per side. The GPU light set uploads a light's texture
// with a full RGBA32F mip chain whenever it changes (every frame for the bouncing square): 2048^2 is
// 85 MB per upload, already far more detail than the 16 x 16 VPLs the area-light technique samples.
inline constexpr int kMaxAreaTextureResolution = 2048;

// Everything areaTextureAt() relies on: the texture only on an area light; frames present, in range,
// non-empty, of one size, with finite non-negative texels, shown at a positive rate; a bouncing square
// of resolution in [1, kMaxAreaTextureResolution], size in (0, 1], finite motion. `where` starts the
// message. finalizeScene calls it, and so do the reference renderers (scenes built in code skip it).
Expected<void> checkAreaTexture(const Scene& scene, const Light& light, const std::string& where);

// The multiplier image of `light` at time t (seconds), or nullptr for an untextured light (uniform 1).
// A procedural frame is rendered into `scratch` and the returned pointer points there; an image frame
// points into scene.textures. The light's texture must be valid (checkAreaTexture).
const Image* areaTextureAt(const Scene& scene, const Light& light, float t, Image& scratch);

// Index of the sequence frame shown at time t: floor(t * frameRate) modulo the frame count (t < 0 holds
// frame 0).
size_t areaTextureFrame(const AreaTexture& texture, float t);

// The bouncing square's centre (u, v) at time t: each coordinate moves at its velocity and reflects off
// [size/2, 1 - size/2].
glm::vec2 bouncingSquareCentre(const AreaTexture& texture, float t);

// Renders the bouncing-square pattern at time t: each texel holds the fraction of its area the square
// covers (exact box coverage), so the mean equals squareSize^2.
Image renderBouncingSquare(const AreaTexture& texture, float t);

// Mean of an image's texels (the average multiplier over the rectangle: texels have equal areas).
glm::vec3 imageMean(const Image& image);

// Mean multiplier of the light's texture at time t (1 for an untextured light).
glm::vec3 areaTextureMean(const Scene& scene, const Light& light, float t);

}  // namespace bounce
