// Looking up a paraboloid shadow map (Brabec et al. 2002; as rendered by paraboloid.vert/.frag): the
// hemisphere around a VPL's normal n maps to the unit disc by uv = (w.t, w.b) / (1 + w.n), w the unit
// direction from the VPL to the receiver, b = n x t; the map stores distance / far. Shared by iir
// (Laine et al. 2007) and area-light's shadow-map baseline (Nichols 2010 §5.4.6).
// Returns the filtered visibility (sampler2DArrayShadow with linear filtering: 2x2 PCF) of a receiver
// at distance d along w, or 0 when w lies behind the VPL's hemisphere.
float paraboloidVisibility(sampler2DArrayShadow maps, float layer, vec3 w, float d, vec3 n, vec3 t, float far,
                           float depthBias) {
    float cosV = dot(n, w);
    if (cosV <= 0.0) return 0.0;
    vec3 b = cross(n, t);
    vec2 uv = vec2(dot(w, t), dot(w, b)) / (1.0 + cosV);
    return texture(maps, vec4(uv * 0.5 + 0.5, layer, d / far - depthBias));
}
