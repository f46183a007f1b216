// Depth-only pass for 2D shadow maps (spot: perspective, directional: orthographic).
// Inputs: render/scene.vert. Outputs: depth only.
void main() {}
