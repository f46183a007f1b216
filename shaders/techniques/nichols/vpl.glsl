// The VPL cache of Nichols (2010) §4.2.1.2: one record per virtual point light, read coherently by
// every gather. Written by techniques/nichols/vpl_extract.comp (regular grid) and isr_clusters.comp.
struct Vpl {
    vec4 position;  // xyz world position; w 1 if the VPL carries light, else 0
    vec4 normal;    // xyz unit normal; w patch area A_j in m^2 (Eq. 4.3)
    vec4 flux;      // rgb reflected flux Phi_j in W; w number of RSM texels represented
};

// Irradiance at x (normal n) from VPL v, W/m^2, no visibility. Eq. 3.2 (point form factor with a
// minimum r^2 clamp) when diskArea is false, Eq. 4.1's disk-to-point form factor when true.
vec3 vplIrradiance(Vpl v, vec3 x, vec3 n, bool diskForm, float minDistance2) {
    vec3 d = v.position.xyz - x;
    float r2 = max(dot(d, d), 1e-12);
    vec3 l = d * inversesqrt(r2);
    float cosReceiver = max(dot(n, l), 0.0);
    float cosSender = max(dot(v.normal.xyz, -l), 0.0);
    float denominator = diskForm ? 3.14159265358979 * r2 + v.normal.w : 3.14159265358979 * max(r2, minDistance2);
    return v.flux.rgb * (cosReceiver * cosSender / denominator);
}
