// The environment light (renderer/scene/environment_map.h) in GLSL: the backdrop camera rays see where they leave
// the scene, and the sky's direct light at a surface through the probes' sky atlas.
//
//   vec3 environmentBackdrop(vec2 fragCoord)   radiance of the environment seen through pixel fragCoord
//                                               (light.background not included)
//   vec3 probeSkyIrradiance(vec3 X, vec3 n)    (#ifdef DEEPGI_SKY, after probe_volume.glsl) irradiance (W/m^2)
//                                               from the environment at X, normal n, with the probes' visibility
//
// Inputs: uniform vec4 uEnvironment = (environment.sky_radiance x intensity, environment.intensity, 1 with a map, 0);
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
    L += uEnvironment.y * textureLod(uEnvironmentMap, equirectFromDirection(d), lod).rgb;
#endif
    return L;
}

#ifdef DEEPGI_SKY
uniform sampler2D uProbeSky;

// probeIrradianceWeighted()'s weights (probe_volume.glsl) over the sky atlas; C++: ProbeVolume::skyIrradiance().
vec3 probeSkyIrradiance(vec3 X, vec3 n) {
    if (any(isnan(X)) || any(isinf(X)) || any(isnan(n)) || any(isinf(n)) || !(dot(n, n) > 1e-12)) return vec3(0.0);
    vec3 spacing = uProbeSpacing.xyz;
    ivec3 last = uProbeCounts.xyz - 1;
    vec3 biased = X + n * uProbeLo.w;
    vec3 g = clamp((biased - uProbeLo.xyz) / spacing - 0.5, vec3(-1.0), vec3(last));
    ivec3 base = clamp(ivec3(floor(g)), ivec3(0), last - 1);
    vec3 alpha = clamp(g - vec3(base), 0.0, 1.0);
    vec2 skySize = vec2(textureSize(uProbeSky, 0)), depthSize = vec2(textureSize(uProbeDepth, 0));
    vec3 sum = vec3(0.0);
    float total = 0.0;
    for (int i = 0; i < 8; ++i) {
        ivec3 o = ivec3(i & 1, (i >> 1) & 1, (i >> 2) & 1);
        ivec3 c = base + o;
        int probe = c.x + uProbeCounts.x * (c.y + uProbeCounts.y * c.z);
        vec4 data = texelFetch(uProbeData, ivec2(probe % uProbeCounts.w, probe / uProbeCounts.w), 0);
        if (data.w < 0.5) continue;
        vec3 probePos = uProbeLo.xyz + (vec3(c) + 0.5) * spacing + data.xyz;
        vec3 tri3 = mix(1.0 - alpha, alpha, vec3(o));
        float trilinear = max(0.001, tri3.x * tri3.y * tri3.z);
        vec3 toProbe = probePos - X;
        float toProbeLen = length(toProbe);
        float wrap = toProbeLen > 0.0 ? (dot(toProbe / toProbeLen, n) + 1.0) * 0.5 : 1.0;
        float weight = wrap * wrap + 0.2;
        vec3 probeToPoint = biased - probePos;
        float dist = length(probeToPoint);
        if (dist > 0.0) {
            vec2 m = texture(uProbeDepth, probeAtlasUv(probe, uProbeTexels.y, probeToPoint / dist, depthSize)).rg;
            if (dist > m.x) {
                float variance = abs(m.y - m.x * m.x);
                float d = dist - m.x;
                float chebyshev = variance / (variance + d * d);
                weight *= max(chebyshev * chebyshev * chebyshev, 0.05);
            }
        }
        weight = max(weight, 1e-6);
        const float crush = 0.2;
        if (weight < crush) weight *= weight * weight / (crush * crush);
        weight *= trilinear;
        sum += weight * texture(uProbeSky, probeAtlasUv(probe, uProbeTexels.x, n, skySize)).rgb;
        total += weight;
    }
    return total > 0.0 ? sum / total : vec3(0.0);
}
#endif
