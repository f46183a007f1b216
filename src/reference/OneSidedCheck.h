#pragma once
// One-sided surfaces that were probably wound the wrong way (docs/scene.md "One-sided or
// two-sided"): a cheap CPU check that `bounce render`, `view`, `reference` and `photon-map` run on
// scene files (not on built-in scenes, which are authored to be seen from the front).
#include "scene/Scene.h"

#include <glm/vec2.hpp>

#include <string>
#include <vector>

namespace bounce {

struct OneSidedCheckOptions {
    // A one-sided object whose back is the first surface camera rays meet over at least this share of
    // the image is reported (the GPU renderers discard those fragments and show what lies behind).
    float backFacingImageShare = 0.1f;
    // Camera rays across the image's width (rows follow the aspect): 64 x 64 rays on a square image,
    // enough for a 10 % share and a few milliseconds of Embree.
    int raysAcross = 64;
};

// One message per finding, each naming the scene file and the object:
//   "FILE: object 'NAME' is one-sided and seen from behind over P% of the image at frame F: ..."
//   "FILE: object 'NAME' is one-sided and every light is behind it or in its plane at frame F: ..."
// `size` gives the image's aspect; the scene is taken at `frame` (its time frame / frameRate).
std::vector<std::string> checkOneSidedSurfaces(const Scene& scene, glm::ivec2 size, uint32_t frame,
                                               const OneSidedCheckOptions& options = {});

}  // namespace bounce
