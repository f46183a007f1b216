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

// The VPL of a light-space patch (an isr cluster, a hisr tree node): `cell` of `level` in a pyramid
// whose level 0 is the RSM, with the patch's pyramid geometry g (xyz weighted position sum, w weight) and
// flux f (rgb summed flux, w area). It sits on the RSM sample at the patch's centre (that texel's position
// and normal: the thesis's VPLs are samples of a dense regular sampling, Fig. 4.7), with the patch's
// summed flux and area; the patch's mean only where that texel saw nothing. A mean point floats off the
// surfaces when a patch of the finest allowed level still spans a discontinuity, and lit receivers next
// to it got bright spots (docs/techniques/isr.md, known artifacts).
Vpl patchVpl(sampler2DArray geometry, sampler2DArray normals, ivec3 cell, int level, vec4 g, vec4 f) {
    int block = 1 << level;
    ivec3 centre = ivec3(min(cell.xy * block + block / 2, textureSize(geometry, 0).xy - 1), cell.z);
    vec4 sampleGeometry = texelFetch(geometry, centre, 0);
    bool onSample = sampleGeometry.w > 0.0;
    Vpl v;
    v.position = vec4(onSample ? sampleGeometry.xyz / sampleGeometry.w : g.xyz / g.w, 1.0);
    vec3 normal = onSample ? texelFetch(normals, centre, 0).xyz : texelFetch(normals, cell, level).xyz;
    v.normal = vec4(normalize(normal + vec3(0.0, 0.0, 1e-12)), f.w);
    v.flux = vec4(f.rgb, g.w);
    return v;
}
