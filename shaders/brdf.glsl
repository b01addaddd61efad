// The glTF metallic-roughness specular lobe (appendix B): GGX D, Smith height-correlated V, Schlick F.
// GLSL twin of renderer/scene/brdf.h (keep the two in step).
const float BRDF_MIN_ALPHA = 0.002;

float ggxD(float nh, float alpha) {
    float a2 = alpha * alpha;
    float d = nh * nh * (a2 - 1.0) + 1.0;
    return a2 / (PI * d * d);
}
float smithV(float nl, float nv, float alpha) {
    float a2 = alpha * alpha;
    float s = nl * sqrt(nv * nv * (1.0 - a2) + a2) + nv * sqrt(nl * nl * (1.0 - a2) + a2);
    return s > 0.0 ? 0.5 / s : 0.0;
}
vec3 schlickF(vec3 f0, float vh) {
    float m = clamp(1.0 - vh, 0.0, 1.0);
    float m2 = m * m;
    return f0 + (1.0 - f0) * (m2 * m2 * m);
}
// F * D * V for unit n, v (to the viewer), l (to the light); roughness is perceptual (alpha = roughness^2).
vec3 ggxSpecular(vec3 n, vec3 v, vec3 l, vec3 f0, float roughness) {
    float nl = dot(n, l), nv = dot(n, v);
    if (nl <= 0.0 || nv <= 0.0) return vec3(0.0);
    float r = clamp(roughness, 0.0, 1.0);
    float alpha = max(BRDF_MIN_ALPHA, r * r);
    vec3 h = normalize(v + l);
    return schlickF(f0, dot(v, h)) * (ggxD(max(dot(n, h), 0.0), alpha) * smithV(nl, nv, alpha));
}
