// Min-max mipmap pyramid of Nichols (2010) §3.2.2 (checklist item 4), shared by the eye-space (camera
// G-buffer) and light-space (RSM) pyramids. Every level is an image2DArray (layers: 1 for the eye, 1
// or 6 for the RSM). Texel record (RGBA32F each):
//   geometry: xyz sum of positions,  w number of covered base texels
//   normal:   xyz sum of normals,    w max relative depth derivative sqrt(dz/dx^2 + dz/dy^2) / z (max-mipmap);
//             eye pyramid with linear depth (§3.2.2.1): w min view depth (kDepthOfEmpty where uncovered)
//   normalMin:xyz per-component min, w number of uncovered base texels
//   normalMax:xyz per-component max, w max depth (eye: view depth; light: light distance ||V_j||, Eq. 4.8)
//   flux:     rgb summed reflected flux (W), w summed patch area (m^2)   (light pyramid only)
// refine (R32F): 1 where the cell or one of its descendants must be refined (computed in pyramid_flag.comp).
const float kNormalEmptyMin = 2.0;   // normalMin of an empty cell (above any unit component)
const float kNormalEmptyMax = -2.0;
const float kDerivativeOfEdge = 1e9;
const float kDepthOfEmpty = 1e30;     // min-depth chain (linear depth) of an uncovered texel  // relative depth derivative of a pixel next to an uncovered one
