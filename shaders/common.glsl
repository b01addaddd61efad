// Frame-wide uniforms and helpers shared by every pass. Mirrors renderer/core/frame_uniforms.h (std140).
layout(std140, binding = 0) uniform FrameUniforms {
    mat4 uView;
    mat4 uProj;
    mat4 uViewProj;
    mat4 uInvViewProj;
    mat4 uPrevViewProj;
    mat4 uPrevInvViewProj;
    vec4 uCameraPos;      // xyz; w = 1 perspective, 0 orthographic
    vec4 uCameraForward;  // xyz
    vec4 uPrevCameraPos;  // xyz; w = perspective flag of last frame
    vec4 uPrevCameraForward;
    vec4 uViewport;       // width, height, 1/width, 1/height
    vec4 uClip;           // near, far, projScale (pixels per scene unit at distance 1; ortho: per unit), frame index
    vec4 uPrevClip;       // near, far of last frame
    vec4 uBackground;     // rgb backdrop radiance
    vec4 uRadiosityGrid;  // x = d: radiosity pixel p stands for screen pixel p * d + d / 2; yz = the grid's size
    vec4 uTapSample;      // x = L, the gather's finest tap level (radiosity.min_mip); yz = the level-0 pixel of each
                          // 2^L block that level L's texel samples (layer 2 may be drawn there directly)
};

// Unit direction from P to the camera (perspective) or against the view axis (orthographic).
vec3 viewDirection(vec3 P) {
    if (uCameraPos.w < 0.5) return -normalize(uCameraForward.xyz);
    vec3 v = uCameraPos.xyz - P;
    float len = length(v);
    return len > 0.0 ? v / len : -normalize(uCameraForward.xyz);
}

// The screen pixel a radiosity-grid pixel stands for (itself at full resolution).
ivec2 screenPixelOfRadiosity(ivec2 p) {
    int d = int(uRadiosityGrid.x);
    return min(p * d + d / 2, ivec2(uViewport.xy) - 1);
}
// The radiosity-grid pixel covering a screen pixel.
ivec2 radiosityPixelOfScreen(ivec2 pix) { return min(pix / int(uRadiosityGrid.x), ivec2(uRadiosityGrid.yz) - 1); }

const float PI = 3.14159265358979;
// Compile-time bounds of every loop whose count is a uniform (a loop runs to a constant maximum and breaks at the
// count, so no uniform value can make a shader run unbounded). Each is at least its setting's maximum in
// renderer/core/settings.def (tests/test_shader_loops.cpp checks that).
const int MAX_SPIRAL_TAPS = 99;   // radiosity.samples
const int MAX_MIP_LEVELS = 16;    // mip levels of a texture up to 32768 texels
// The R11F_G11F_B10F maximum of the B channel (R and G reach 65024): one limit for all three channels, so a clamped
// pixel stays grey.
const float MAX_RADIANCE = 64512.0;

// Finite, non-negative and below the format maximum: everything a later frame reads goes through this.
vec3 sanitize(vec3 v) {
    if (any(isnan(v)) || any(isinf(v))) return vec3(0.0);
    return clamp(v, vec3(0.0), vec3(MAX_RADIANCE));
}

// sanitize(), then rounded to an R11F_G11F_B10F value (R, G: 6 mantissa bits, B: 5; denormals below 2^-14) so that
// the store itself is exact: stochastically, up or down with the probabilities that make the expected stored value
// equal v (the dither is a hash of the pixel and the frame). llvmpipe truncates when it converts to this format; in
// a history blended with alpha = 0.92 every frame, truncation ratchets the value down (a decrease always survives
// the store, an increase only when it is at least one step), B with its coarser step most: white surfaces turned
// yellow (up to 17% between channels) and the bounce feedback lost energy. Round-to-nearest still stalls a
// history up to +-6 steps away from its input; stochastic rounding does not (tests/test_hard_stability.cpp,
// docs/ROBUSTNESS.md). Values already representable are stored unchanged.
vec3 sanitizeR11G11B10(vec3 v, vec2 fragCoord) {
    v = sanitize(v);
    ivec3 e;
    frexp(v, e);                                                         // v = m * 2^e, m in [0.5, 1)
    vec3 scale = exp2(vec3(7.0, 7.0, 6.0) - vec3(max(e, ivec3(-13))));  // 1 / step (the denormal step below 2^-14)
    uint h = (uint(fragCoord.x) * 1664525u) ^ (uint(fragCoord.y) * 1013904223u) ^ (uint(uClip.w) * 2654435769u);
    h = (h ^ (h >> 16u)) * 2246822519u;
    h = (h ^ (h >> 13u)) * 3266489917u;
    float u = float(h >> 8u) * (1.0 / 16777216.0);  // [0, 1), the same for the three channels (grey stays grey)
    vec3 r = min(floor(v * scale + u) / scale, vec3(MAX_RADIANCE));
    // Within B's last step (1024) of the maximum every channel goes to it: R and G, with finer steps, would
    // otherwise stop short of a B that rounded up, and a saturated grey would turn yellow.
    return mix(r, vec3(MAX_RADIANCE), step(vec3(MAX_RADIANCE - 1024.0), v));
}

// Distance along the view axis from a [0,1] depth-buffer value. clip = (near, far), persp = 1 or 0.
float eyeDepth(float d, vec2 clip, float persp) {
    float n = clip.x, f = clip.y;
    if (persp > 0.5) {
        float z = d * 2.0 - 1.0;
        return 2.0 * n * f / max(f + n - z * (f - n), 1e-30);
    }
    return n + d * (f - n);
}
float eyeDepthCurrent(float d) { return eyeDepth(d, uClip.xy, uCameraPos.w); }
float eyeDepthPrevious(float d) { return eyeDepth(d, uPrevClip.xy, uPrevCameraPos.w); }

// World position of a pixel position (in pixels, centre = +0.5) and depth-buffer value.
vec3 worldFromDepth(vec2 pixel, float d, mat4 invViewProj) {
    vec4 ndc = vec4(pixel * uViewport.zw * 2.0 - 1.0, d * 2.0 - 1.0, 1.0);
    vec4 w = invViewProj * ndc;
    return w.xyz / w.w;
}

// Octahedral unit-vector encoding into [-1,1]^2 (stored in RG8_SNORM).
vec2 signNotZero(vec2 v) { return vec2(v.x >= 0.0 ? 1.0 : -1.0, v.y >= 0.0 ? 1.0 : -1.0); }
vec2 octEncode(vec3 n) {
    n /= max(abs(n.x) + abs(n.y) + abs(n.z), 1e-20);
    vec2 p = n.xy;
    if (n.z < 0.0) p = (1.0 - abs(p.yx)) * signNotZero(p);
    return p;
}
vec3 octDecode(vec2 e) {
    vec3 n = vec3(e, 1.0 - abs(e.x) - abs(e.y));
    if (n.z < 0.0) n.xy = (1.0 - abs(n.yx)) * signNotZero(n.xy);
    float l = length(n);
    return l > 0.0 ? n / l : vec3(0.0, 0.0, 1.0);
}

bool isSky(float d) { return d >= 1.0; }

// A Normal texel (RG8_SNORM, octahedral) as one float, its two bytes exactly: Radiosity Geometry's w (sky: -1).
float packNormalCode(vec2 e) {
    ivec2 k = clamp(ivec2(round(e * 127.0)), ivec2(-127), ivec2(127)) + 128;
    return float(k.x * 256 + k.y);
}
vec3 unpackNormalCode(float c) {
    int k = int(c);
    return octDecode(vec2(ivec2(k >> 8, k & 255) - 128) / 127.0);
}

// The spiral taps of the gather and the AO (technique.md 1.6): G3D's per-pixel rotation phi and radial jitter
// (optionally varied with time), and tap i of n: its radius h (pixels, uniform in [0, rss]) and unit direction.
void spiralPixel(ivec2 pix, vec2 fragCoord, float time, out float phi, out float jitter) {
    phi = float((3 * pix.x) ^ (pix.y + pix.x * pix.y)) * 10.0 + time;
    jitter = fract(sin(fragCoord.x * 100.0 + fragCoord.y + time) * 1e5 + sin(fragCoord.y * 1000.0) * 1000.0) * 0.8 + 0.1;
}
vec2 spiralTap(int i, int n, float turns, float phi, float jitter, float rss, out float h) {
    float alpha = (float(i) + jitter) / float(n);
    float theta = alpha * turns * 6.28 + phi;
    h = alpha * rss;
    return vec2(cos(theta), sin(theta));
}

// The level-k texel whose sample texel T of level k + m holds: gather_mips.frag's rotated-grid choice,
// q = clamp(2p + (p.y & 1, p.x & 1)), followed back m levels. In closed form: each step swaps the low bits, so the
// offsets alternate (T.y & 1, T.x & 1), (T.x & 1, T.y & 1), ... from the coarsest step, i.e. the bits m-1, m-3, ...
// take one and m-2, m-4, ... the other; the per-level clamp never binds below a one-texel level
// (2 floor(s/2) - 1 <= s - 1), so one clamp at the end gives the same texel (checked for every texel of 6 sizes).
ivec2 rotatedGridSource(ivec2 T, int m) {
    int mask = (1 << m) - 1;
    int first = mask & ((m & 1) != 0 ? 0x55555555 : 0x2AAAAAAA), second = mask & ~first;
    int a = T.x & 1, b = T.y & 1;
    return (T << m) + ivec2(b * first + a * second, a * first + b * second);
}
// The full-resolution pixel whose sample mip texel T of level m holds (size = level-0 size). Level L = uTapSample.x,
// the gather's finest, samples one fixed pixel of each 2^L block (uTapSample.yz), so that layer 2 can be rasterised
// at level L with the very samples layer 1's level L takes from level 0; the coarser levels pick from level L by the
// rotated grid. Level 0 is itself; the levels between 0 and L are neither built nor read (this gives level L's
// pixel for them). Without a branch: llvmpipe would run both sides (the gather 1.04 x).
ivec2 sourcePixel(ivec2 T, int m, ivec2 size) {
    int L = int(uTapSample.x);
    ivec2 q = min((rotatedGridSource(T, max(m - L, 0)) << L) + ivec2(uTapSample.yz), size - 1);
    return m == 0 ? T : q;
}
