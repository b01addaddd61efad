// The environment light (renderer/scene/environment_map.h) in GLSL: the backdrop camera rays see where they leave
// the scene, and the sky's direct light at a surface through the probes' sky atlas.
//
//   vec3 environmentBackdrop(vec2 fragCoord)   radiance of the environment seen through pixel fragCoord
//                                               (light.background not included)
//   vec3 probeSkyIrradiance(vec3 X, vec3 n)    (#ifdef DEEPGI_SKY, after probe_volume.glsl) irradiance (W/m^2)
//                                               from the environment at X, normal n, with the probes' visibility
//
// Inputs: uniform vec4 uEnvironment = (environment.sky_radiance x intensity, environment.intensity, 1 with a map,
//   environment.rotation in radians);
//   #ifdef DEEPGI_ENVIRONMENT_MAP: sampler2D uEnvironmentMap ("Environment Map", equirectangular, row 0 = top =
//   +Y, mip-mapped, repeating in u); #ifdef DEEPGI_SKY: sampler2D uProbeSky ("Probe Sky Irradiance").
uniform vec4 uEnvironment;
#ifdef DEEPGI_ENVIRONMENT_MAP
uniform sampler2D uEnvironmentMap;
#endif

// Unit direction -> (u, t): u = 0.5 + atan2(z, x) / 2pi, t = acos(y) / pi from the top row (environment_map.h).
vec2 equirectFromDirection(vec3 d) {
    return vec2(0.5 + atan(d.z, d.x) * (0.5 / PI), acos(clamp(d.y, -1.0, 1.0)) / PI);
}

// The direction of the camera ray through a point of the screen (perspective or orthographic).
vec3 environmentViewDirection(vec2 fragCoord) {
    vec2 ndc = fragCoord * uViewport.zw * 2.0 - 1.0;
    vec4 a = uInvViewProj * vec4(ndc, -1.0, 1.0), b = uInvViewProj * vec4(ndc, 1.0, 1.0);
    return normalize(b.xyz / b.w - a.xyz / a.w);
}

vec3 environmentBackdrop(vec2 fragCoord) {
    vec3 L = vec3(uEnvironment.x);
#ifdef DEEPGI_ENVIRONMENT_MAP
    vec3 d = environmentViewDirection(fragCoord);
    // The mip level from the angle one pixel spans (explicit, not from derivatives: no seam at u = 0, no
    // derivatives in the caller's non-uniform branch).
    vec3 dx = environmentViewDirection(fragCoord + vec2(1.0, 0.0)), dy = environmentViewDirection(fragCoord + vec2(0.0, 1.0));
    float pixelAngle = max(acos(clamp(dot(d, dx), -1.0, 1.0)), acos(clamp(dot(d, dy), -1.0, 1.0)));
    float texelAngle = PI / float(textureSize(uEnvironmentMap, 0).y);
    float lod = max(0.0, log2(max(pixelAngle / texelAngle, 1e-6)));
    // The map's own direction R_y(-rotation) d (environment_map.h).
    const float c = cos(uEnvironment.w), s = sin(uEnvironment.w);
    const vec3 m = vec3(d.x * c - d.z * s, d.y, d.x * s + d.z * c);
    L += uEnvironment.y * textureLod(uEnvironmentMap, equirectFromDirection(m), lod).rgb;
#endif
    return L;
}

#ifdef DEEPGI_SKY
uniform sampler2D uProbeSky;

// probeIrradianceWeighted()'s probes and weights over the sky atlas; C++: ProbeVolume::skyIrradiance().
vec3 probeSkyIrradiance(vec3 X, vec3 n, vec3 V) { return probeAtlasWeighted(uProbeSky, X, n, V).rgb; }
vec3 probeSkyIrradiance(vec3 X, vec3 n) { return probeSkyIrradiance(X, n, vec3(0.0)); }
#endif
