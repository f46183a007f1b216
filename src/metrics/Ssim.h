#pragma once
// Structural similarity (Wang, Bovik, Sheikh & Simoncelli, "Image Quality Assessment: From Error
// Visibility to Structural Similarity", IEEE TIP 2004), with the paper's parameters: an 11x11
// circular Gaussian window of sigma 1.5 pixels, K1 = 0.01, K2 = 0.03, dynamic range L = 1.
//
// bounce applies it to display images (sRGB-encoded values in [0, 1], i.e. toDisplay() output)
// per RGB channel and averages the three channels, so hue shifts count as well as luminance ones.
#include "core/Image.h"
#include "metrics/ErrorMap.h"

namespace bounce {

// Per-pixel SSIM (mean over the three channels), in [-1, 1]; 1 where the windows are identical.
// Windows that cross the border see replicated edge pixels.
ErrorMap ssimMap(const Image& testDisplay, const Image& referenceDisplay);

// Mean SSIM: the map averaged over the pixels whose whole 11x11 window lies inside the image (the
// paper's "valid" region); images smaller than the window in either direction use every pixel.
double meanSsim(const Image& testDisplay, const Image& referenceDisplay);

}  // namespace bounce
