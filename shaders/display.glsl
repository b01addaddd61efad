// The display image from linear radiance: exposure, the tone map, sRGB encoding (composite.frag, composite_sky.frag).
uniform float uExposure;   // linear scale 2^EV
uniform int uTonemap;      // 0 clamp, 1 ACES fit

vec3 aces(vec3 x) { return clamp((x * (2.51 * x + 0.03)) / (x * (2.43 * x + 0.59) + 0.14), 0.0, 1.0); }
vec3 toSrgb(vec3 c) {
    c = clamp(c, 0.0, 1.0);
    return mix(c * 12.92, 1.055 * pow(c, vec3(1.0 / 2.4)) - 0.055, step(vec3(0.0031308), c));
}
vec4 displayColor(vec3 L) {
    vec3 x = L * uExposure;
    return vec4(toSrgb(uTonemap == 1 ? aces(x) : x), 1.0);
}
