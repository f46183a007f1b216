// The lobe-centred light samples of Nichols 2010 §5.3.2.1 (checklist item 17): where the reflection
// direction R meets light L's plane, the lobe's footprint there, and the 25 points of the 5 x 5 grid
// centred on it (spacing = footprint diameter / 5). Shared by the specular gather and the variance
// visibility's moment pass (§5.3.3.3), which must query the same points. Needs area_common.glsl.
const int kLobeGrid = 5;       // §5.3.2.1: 5 x 5 = 25 lobe-centred samples
const int kLobeQueries = 24;   // §5.3.3.3: one corner of the grid sends no visibility query

struct LobeFootprint {
    float t;           // distance along R to the light's plane (<= 0: R does not meet it in front)
    float radius;      // lobe cross-section radius there (m)
    float vplsInLobe;  // VPL cells the footprint covers (its area / a cell's, the ellipse of an oblique R)
};

LobeFootprint lobeFootprint(AreaLightGpu L, vec3 x, vec3 R, float theta) {
    LobeFootprint f;
    float denom = dot(R, L.normal.xyz);
    f.t = abs(denom) > 1e-6 ? dot(L.centre.xyz - x, L.normal.xyz) / denom : -1.0;
    f.radius = f.t > 0.0 ? f.t * tan(min(theta, 1.5)) : 0.0;
    float side = L.texture.w;
    float cellArea = L.normal.w / (side * side);
    f.vplsInLobe = f.t > 0.0 ? kPi * f.radius * f.radius / max(abs(denom), 1e-3) / cellArea : 1e9;
    return f;
}

// Sample k (0..24, row-major over the 5 x 5 grid; 24 is the corner without a query): its point y and
// light coordinates uv; false when it falls off the rectangle.
bool lobeSamplePoint(AreaLightGpu L, vec3 x, vec3 R, LobeFootprint f, int k, out vec3 y, out vec2 uv) {
    vec3 eu = L.edgeU.xyz / L.edgeU.w, ev = L.edgeV.xyz / L.edgeV.w;
    float h = 2.0 * f.radius / float(kLobeGrid);
    int a = k % kLobeGrid, b = k / kLobeGrid;
    y = x + f.t * R + (float(a) - 2.0) * h * eu + (float(b) - 2.0) * h * ev;
    vec3 dy = y - L.centre.xyz;
    uv = vec2(dot(dy, eu) / L.edgeU.w, dot(dy, ev) / L.edgeV.w) + 0.5;
    return all(greaterThanEqual(uv, vec2(0.0))) && all(lessThanEqual(uv, vec2(1.0)));
}
