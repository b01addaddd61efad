// World-space irradiance probes (DDGI), the GLSL side of renderer/probes/probe_volume.h; the same math as
// ProbeVolume::irradiance().
//
//   vec3 probeIrradiance(vec3 X, vec3 n)        irradiance (W/m^2) at world position X on a surface of unit normal
//                                                n; a Lambertian receiver's indirect radiance is albedo/PI * it.
//   vec4 probeIrradianceWeighted(vec3 X, vec3 n) rgb as above, a = the summed probe weight (0 = no probe answers;
//                                                about 1 where the 8 surrounding probes all see X).
//
// Inputs (the including shader may #define the binding points before including this file):
//   uniform block ProbeVolumeUniforms, std140, binding PROBE_VOLUME_UBO_BINDING (default 2), filled from
//     ProbeVolume::uniforms() (C++ struct ProbeVolumeUniforms, 80 bytes):
//       vec4  uProbeLo;       xyz = corner of the covered box (probe (0,0,0) is at uProbeLo + spacing/2), w unused
//       vec4  uProbeSpacing;  xyz = spacing per axis (scene units), w = 1 once every active probe was updated
//       ivec4 uProbeCounts;   xyz = probes per axis, w = atlas tiles per row (probe i: tile (i % w, i / w))
//       ivec4 uProbeTexels;   x = irradiance interior texels I, y = depth interior texels D, z = active probes,
//                             w = radiance interior texels R
//       vec4  uProbeBias;     x = normal bias, y = view bias (scene units)
//   sampler2D uProbeIrradiance  unit PROBE_IRRADIANCE_UNIT (default 2): "Probe Irradiance", RGBA32F,
//                               tiles of (I+2)^2 texels, GL_LINEAR, clamp to edge
//   sampler2D uProbeDepth       unit PROBE_DEPTH_UNIT (default 3): "Probe Depth", RG32F, tiles of (D+2)^2,
//                               GL_LINEAR, clamp to edge
//   sampler2D uProbeData        unit PROBE_DATA_UNIT (default 5): "Probe Data", RGBA32F, one texel per probe,
//                               read with texelFetch (xyz offset, w state: > 0.5 = active)
//   sampler2D uProbeRadiance    unit PROBE_RADIANCE_UNIT (default 6): "Probe Radiance", RGBA32F, tiles of (R+2)^2
//                               texels (R = uProbeTexels.w), read with texelFetch: the radiance arriving per
//                               direction; only probeRadianceAt() reads it
#ifndef PROBE_VOLUME_UBO_BINDING
#define PROBE_VOLUME_UBO_BINDING 2
#endif
#ifndef PROBE_IRRADIANCE_UNIT
#define PROBE_IRRADIANCE_UNIT 2
#endif
#ifndef PROBE_DEPTH_UNIT
#define PROBE_DEPTH_UNIT 3
#endif
#ifndef PROBE_DATA_UNIT
#define PROBE_DATA_UNIT 5
#endif
#ifndef PROBE_RADIANCE_UNIT
#define PROBE_RADIANCE_UNIT 6
#endif

layout(std140, binding = PROBE_VOLUME_UBO_BINDING) uniform ProbeVolumeUniforms {
    vec4 uProbeLo;
    vec4 uProbeSpacing;
    ivec4 uProbeCounts;
    ivec4 uProbeTexels;
    vec4 uProbeBias;
};
#ifdef PROBE_VOLUME_FIXED_UNITS  // standalone use (tests); in the pipeline the renderer assigns units from the table
layout(binding = PROBE_IRRADIANCE_UNIT) uniform sampler2D uProbeIrradiance;
layout(binding = PROBE_DEPTH_UNIT) uniform sampler2D uProbeDepth;
layout(binding = PROBE_DATA_UNIT) uniform sampler2D uProbeData;
layout(binding = PROBE_RADIANCE_UNIT) uniform sampler2D uProbeRadiance;
#else
uniform sampler2D uProbeIrradiance;
uniform sampler2D uProbeDepth;
uniform sampler2D uProbeData;
uniform sampler2D uProbeRadiance;
#endif

// A probe's tile (column, row) in an atlas. Float division: llvmpipe runs it on all lanes at once, an integer
// division one lane at a time. Exact for fewer than 2^22 probes (the row is at most probes / columns).
ivec2 probeTile(int probe) {
    int row = int((float(probe) + 0.5) / float(uProbeCounts.w));
    return ivec2(probe - row * uProbeCounts.w, row);
}

float probeSignNotZero(float v) { return v >= 0.0 ? 1.0 : -1.0; }

// Unit direction -> [-1,1]^2 (renderer/probes/octahedral.h).
vec2 probeOctEncode(vec3 d) {
    vec2 p = d.xy / (abs(d.x) + abs(d.y) + abs(d.z));
    if (d.z < 0.0) p = vec2((1.0 - abs(p.y)) * probeSignNotZero(p.x), (1.0 - abs(p.x)) * probeSignNotZero(p.y));
    return p;
}

// Texture coordinate of direction d in the tile (column, row) of an atlas with n interior texels per tile edge.
vec2 probeAtlasUv(ivec2 tile, int n, vec3 d, vec2 atlasSize) {
    vec2 origin = vec2(tile * (n + 2) + 1);
    return (origin + (probeOctEncode(d) * 0.5 + 0.5) * float(n)) / atlasSize;
}
vec2 probeAtlasUv(int probe, int n, vec3 d, vec2 atlasSize) { return probeAtlasUv(probeTile(probe), n, d, atlasSize); }

// The cell of probes around X (surface normal n, seen from unit direction V, or V = 0): its first corner, the
// trilinear fractions, the biased receiver (moved along n and towards its viewer: C++ ProbeVolume::probeWeights).
bool probeCell(vec3 X, vec3 n, vec3 V, out ivec3 base, out vec3 alpha, out vec3 biased) {
    base = ivec3(0);
    alpha = vec3(0.0);
    biased = X;
    if (any(isnan(X)) || any(isinf(X)) || any(isnan(n)) || any(isinf(n)) || !(dot(n, n) > 1e-12)) return false;
    ivec3 last = uProbeCounts.xyz - 1;
    biased = X + n * uProbeBias.x + V * uProbeBias.y;
    vec3 g = clamp((biased - uProbeLo.xyz) / uProbeSpacing.xyz - 0.5, vec3(-1.0), vec3(last));
    base = clamp(ivec3(floor(g)), ivec3(0), last - 1);
    alpha = clamp(g - vec3(base), 0.0, 1.0);
    return true;
}

// Corner i (0..7) of that cell: the probe's index (-1 = inside geometry or unused) and its unnormalised weight.
int probeCorner(int i, ivec3 base, vec3 alpha, vec3 X, vec3 n, vec3 biased, vec2 depthSize, out float weight,
                out vec3 probePos) {
    weight = 0.0;
    ivec3 o = ivec3(i & 1, (i >> 1) & 1, (i >> 2) & 1);
    ivec3 c = base + o;
    int probe = c.x + uProbeCounts.x * (c.y + uProbeCounts.y * c.z);
    vec4 data = texelFetch(uProbeData, probeTile(probe), 0);
    probePos = uProbeLo.xyz + (vec3(c) + 0.5) * uProbeSpacing.xyz + data.xyz;
    if (data.w < 0.5) return -1;  // inside geometry or unused
    vec3 tri3 = mix(1.0 - alpha, alpha, vec3(o));
    float trilinear = max(0.001, tri3.x * tri3.y * tri3.z);
    // Smooth back-face term: probes behind the surface count less.
    vec3 toProbe = probePos - X;
    float toProbeLen = length(toProbe);
    float wrap = toProbeLen > 0.0 ? (dot(toProbe / toProbeLen, n) + 1.0) * 0.5 : 1.0;
    float w = wrap * wrap + 0.2;
    // Chebyshev visibility against the probe's depth moments towards the (biased) receiver.
    vec3 probeToPoint = biased - probePos;
    float dist = length(probeToPoint);
    if (dist > 0.0) {
        vec2 m = texture(uProbeDepth, probeAtlasUv(probe, uProbeTexels.y, probeToPoint / dist, depthSize)).rg;
        if (dist > m.x) {
            float variance = abs(m.y - m.x * m.x);
            float d = dist - m.x;
            float chebyshev = variance / (variance + d * d);
            w *= max(chebyshev * chebyshev * chebyshev, 0.05);
        }
    }
    w = max(w, 1e-6);
    const float crush = 0.2;  // weights below this fall off cubically (fewer leaks)
    if (w < crush) w *= w * w / (crush * crush);
    weight = w * trilinear;
    return probe;
}

// The 8 probes' weighted mean of an atlas laid out as the irradiance one (irradiance, sky), with the weights' sum in
// w; C++: weightedAtlasIrradiance over probeWeights. V: the unit direction towards the receiver's viewer (0: none).
vec4 probeAtlasWeighted(sampler2D atlas, vec3 X, vec3 n, vec3 V) {
    ivec3 base;
    vec3 alpha, biased;
    if (!probeCell(X, n, V, base, alpha, biased)) return vec4(0.0);
    vec2 atlasSize = vec2(textureSize(atlas, 0)), depthSize = vec2(textureSize(uProbeDepth, 0));
    vec3 sum = vec3(0.0);
    float total = 0.0;
    for (int i = 0; i < 8; ++i) {
        float weight;
        vec3 probePos;
        int probe = probeCorner(i, base, alpha, X, n, biased, depthSize, weight, probePos);
        if (probe < 0) continue;
        sum += weight * texture(atlas, probeAtlasUv(probe, uProbeTexels.x, n, atlasSize)).rgb;
        total += weight;
    }
    return total > 0.0 ? vec4(sum / total, total) : vec4(0.0);
}

vec4 probeAtlasWeighted(sampler2D atlas, vec3 X, vec3 n) { return probeAtlasWeighted(atlas, X, n, vec3(0.0)); }

vec4 probeIrradianceWeighted(vec3 X, vec3 n) { return probeAtlasWeighted(uProbeIrradiance, X, n); }

vec3 probeIrradiance(vec3 X, vec3 n, vec3 V) { return probeAtlasWeighted(uProbeIrradiance, X, n, V).rgb; }
vec3 probeIrradiance(vec3 X, vec3 n) { return probeIrradiance(X, n, vec3(0.0)); }

// The 8 probes around X (surface normal n) as their atlas tiles and normalised weights (a probe that does not answer:
// weight 0, tile (0, 0)), once per receiver, for probeRadianceAt() in as many directions as needed; meanPos = the
// probes' weighted mean position. False where no probe answers. The lookups below add every probe's texel times its
// weight without a test (llvmpipe runs both sides of a test anyway) and find its tile without a division.
bool probeSetAt(vec3 X, vec3 n, vec3 V, out ivec2 tiles[8], out float weights[8], out vec3 meanPos) {
    meanPos = X;
    for (int i = 0; i < 8; ++i) {
        tiles[i] = ivec2(0);
        weights[i] = 0.0;
    }
    ivec3 base;
    vec3 alpha, biased;
    if (!probeCell(X, n, V, base, alpha, biased)) return false;
    vec2 depthSize = vec2(textureSize(uProbeDepth, 0));
    float total = 0.0;
    vec3 posSum = vec3(0.0);
    for (int i = 0; i < 8; ++i) {
        vec3 probePos;
        int probe = probeCorner(i, base, alpha, X, n, biased, depthSize, weights[i], probePos);
        if (probe >= 0) {
            tiles[i] = probeTile(probe);
            total += weights[i];
            posSum += weights[i] * probePos;
        } else {
            weights[i] = 0.0;
        }
    }
    if (!(total > 0.0)) return false;
    for (int i = 0; i < 8; ++i) weights[i] /= total;
    meanPos = posSum / total;
    return true;
}

// The irradiance on normal n at the receiver of probeSetAt() (as probeIrradiance(), without recomputing weights).
vec3 probeIrradianceAt(ivec2 tiles[8], float weights[8], vec3 n) {
    vec2 size = vec2(textureSize(uProbeIrradiance, 0));
    vec3 sum = vec3(0.0);
    for (int i = 0; i < 8; ++i)
        sum += weights[i] * texture(uProbeIrradiance, probeAtlasUv(tiles[i], uProbeTexels.x, n, size)).rgb;
    return sum;
}

// The radiance arriving from direction d (unit, away from the receiver) at the receiver of probeSetAt(): each
// probe's texel that d leaves through, unfiltered (the gather's directions change every frame, its filters do the
// rest; a filtered lookup costs llvmpipe 4 texels); C++: ProbeVolume::radiance(). a = the probes' mean distance along
// d to the surface that light comes from (2 x the grid's diagonal for a miss).
// The radiance map's texel that direction d leaves through (as ProbeVolume's octTexel()).
ivec2 probeRadianceTexel(vec3 d) {
    int n = uProbeTexels.w;
    return clamp(ivec2((probeOctEncode(d) * 0.5 + 0.5) * float(n)), ivec2(0), ivec2(n - 1));
}

vec4 probeRadianceDistanceAt(ivec2 tiles[8], float weights[8], vec3 d) {
    int n = uProbeTexels.w;
    ivec2 t = probeRadianceTexel(d) + 1;
    vec4 sum = vec4(0.0);
    for (int i = 0; i < 8; ++i) sum += weights[i] * texelFetch(uProbeRadiance, tiles[i] * (n + 2) + t, 0);
    return sum;
}

vec3 probeRadianceAt(ivec2 tiles[8], float weights[8], vec3 d) { return probeRadianceDistanceAt(tiles, weights, d).rgb; }
