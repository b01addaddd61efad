#version 450 core
// Screen-space radiosity gather over both deep G-buffer layers (Mara et al. 2016, technique.md 1.6), with a
// consistent estimator: the paper's spiral taps, world radius projected to pixels and per-tap mips, but each tap
// stands for the surface patch its share of the screen disk covers, weighted by its form factor
//   E(X) = sum_taps B_Y * cos_X * cos_Y * A_Y / (|Y - X|^2 + A_texel / pi)
// (A_Y = the patch's world area; a texel's area / pi, from the on-axis disk form factor, keeps a near tap bounded),
// both layers' patches counted, each only if visible from X (a march through the layers' depth intervals, and
// for layer 2 the crossing of the layer-1 surface in front of it). It converges to the irradiance from the
// surfaces the two layers hold as taps grow. The covered share of the cosine-weighted hemisphere goes to
// Gather Coverage (the confidence where the screen has no data); the probes fill the rest, per hemisphere sector
// (probes.directional_fill) or as the uncovered share of their irradiance.
#include "common.glsl"
// With the interleaved gather (radiosity.interleave) it runs only where Gather Select chose to (an early depth test
// against Gather Mask); that pass wrote the other pixels' irradiance and every pixel's Radiosity Geometry.
uniform sampler2DArray uDepth;
uniform sampler2DArray uNormal;
uniform sampler2DArray uRadiance;
uniform int uNumSamples;
uniform float uSpiralTurns;
uniform float uRadius;
uniform int uMinMip;
uniform int uMaxMip;
uniform int uLogMaxOffset;
uniform int uTapNormalTest;
uniform int uUseLayer2;
uniform float uTime;  // varies the pattern per frame when temporally varying taps
layout(location = 0) out vec3 oIrradiance;
layout(location = 1) out float oCoverage;
uniform float uThickness;      // assumed thickness behind a layer-1 surface where layer 2 does not bound it
const int MAX_VISIBILITY_STEPS = 16;  // radiosity.visibility_steps
// Largest change of layer 1's eye depth between two march samples, relative to it, that still counts as one surface
// (the occluder hard scene: indirect relL1 30.1 / 27.4 / 23.7 % at 0.05 / 0.1 / 0.25; nothing else moved).
const float CROSS_MAX_JUMP = 0.25;
uniform int uVisibilitySteps;  // march steps per tap (0 = no visibility test)
#ifdef DEEPGI_PROBES
#include "probe_volume.glsl"
#endif
#ifdef DEEPGI_PROBE_DIRECTIONAL_FILL
// The directional fill: the hemisphere around the receiver's normal in 8 sectors of equal cosine-weighted measure
// (1/8 of pi each): 4 quadrants of azimuth (in a tangent frame turned per pixel) x 2 rings split at sin^2 = 1/2.
// The screen's taps fill what they cover of each sector; the probes' radiance the rest.
const int FILL_SECTORS = 8;
const float SECTOR_SHARE = 1.0 / float(FILL_SECTORS);
int fillSector(vec3 d, vec3 t, vec3 b, vec3 n) {
    float z = dot(d, n);
    return (dot(d, t) < 0.0 ? 1 : 0) + (dot(d, b) < 0.0 ? 2 : 0) + (z * z < 0.5 ? 4 : 0);
}
// A cosine-distributed direction inside sector s from two uniform numbers in [0, 1).
vec3 sectorDirection(int s, vec2 u, vec3 t, vec3 b, vec3 n) {
    float a = u.x * (0.5 * PI);
    float s2 = (float(s >> 2) + u.y) * 0.5;  // sin^2 of the polar angle, uniform in the ring
    float st = sqrt(s2), ct = sqrt(max(1.0 - s2, 0.0));
    float sx = (s & 1) != 0 ? -1.0 : 1.0, sy = (s & 2) != 0 ? -1.0 : 1.0;
    return normalize(st * (cos(a) * sx * t + sin(a) * sy * b) + ct * n);
}
uint fillHash(uint x) {  // a 32-bit integer mix (Wellons' lowbias32)
    x ^= x >> 16; x *= 0x7feb352du; x ^= x >> 15; x *= 0x846ca68bu; x ^= x >> 16;
    return x;
}
#endif

// Eye depth (distance along the view axis) of a world point.
float eyeZ(vec3 P) { return dot(P - uCameraPos.xyz, uCameraForward.xyz); }

// World area of the surface seen through one pixel at Y (normal nY).
float pixelArea(vec3 Y, vec3 nY) {
    vec3 c = Y - uCameraPos.xyz;
    float f2 = uClip.z * uClip.z;
    if (uCameraPos.w > 0.5) {
        float dist = max(length(c), 1e-30);
        float z = dot(c, uCameraForward.xyz);
        float cosCam = max(abs(dot(nY, c)) / dist, 1e-3);
        return z * z * z / (dist * f2 * cosCam);
    }
    return 1.0 / (f2 * max(abs(dot(nY, uCameraForward.xyz)), 1e-3));
}

// Screen pixel and eye depth of a world point.
vec2 toPixel(vec3 P) {
    vec4 c = uViewProj * vec4(P, 1.0);
    return (c.xy / c.w * 0.5 + 0.5) * uViewport.xy;
}

// findMSB(max(int(h), 1)) read off the float exponent of that integer (exact below 2^24): llvmpipe expands findMSB
// into a long sequence on each of the ~90 calls per pixel.
int mipFor(float h) {
    int msb = (floatBitsToInt(float(max(int(h), 1))) >> 23) - 127;
    return clamp(msb - uLogMaxOffset, uMinMip, uMaxMip);
}

// One march for both layers of a tap (one set of depth fetches): points evenly spaced on the screen from X's pixel
// a to the tap's pixel b, where the segments X -> Y0 and X -> Y1 (both end on b's pixel ray) have eye depths that
// interpolate as 1/z across the screen (z itself under an orthographic camera). A segment is blocked where it runs
// behind layer 1 by less than that surface's thickness (the interval up to layer 2, at most uThickness).
// Each step's depth is the mip texel's own sample, at the full-resolution pixel it came from (sourcePixel): the
// segment's depth is taken where that pixel projects onto it, and a sample on the receiver's or the tap's tangent
// plane (within 3 % of |Y - X|) is that surface itself, which cannot block (a grazing floor at a wall's foot).
// A segment in front of layer 1 at one sample and behind it at the next, over the same surface, went through it.
void marchOccluded(vec2 a, vec2 b, float hY, vec3 X, vec3 nX, vec3 Y0, vec3 n0, vec3 Y1, vec3 n1, float zX, float zY0,
                   float zY1, bool test0, bool test1, float jitter, ivec2 size, bool twoLayers, out bool occ0,
                   out bool occ1) {
    occ0 = false;
    occ1 = false;
    bool persp = uCameraPos.w > 0.5;
    float iX = persp ? 1.0 / zX : zX, i0 = persp ? 1.0 / zY0 : zY0, i1 = persp ? 1.0 / zY1 : zY1;
    vec2 ab = b - a;
    float abInv = 1.0 / max(dot(ab, ab), 1e-12);
    float e0 = 0.03 * length(Y0 - X), e1 = 0.03 * length(Y1 - X);
    // The previous sample's layer-1 depth and whether each segment ran in front of it there (0 = no sample yet).
    float zLast = 0.0;
    bool front0 = false, front1 = false;
    for (int k = 0; k < MAX_VISIBILITY_STEPS; ++k) {
        if (k >= uVisibilitySteps) break;
        float ts = (float(k) + jitter) / float(uVisibilitySteps);
        ivec2 q = ivec2(mix(a, b, ts));
        if (any(lessThan(q, ivec2(0))) || any(greaterThanEqual(q, size))) { zLast = 0.0; continue; }
        int m = mipFor(ts * hY);
        ivec2 T = q >> m;
        float d1 = texelFetch(uDepth, ivec3(T, 0), m).r;
        if (isSky(d1)) { zLast = 0.0; continue; }
        vec2 src = vec2(sourcePixel(T, m, size)) + 0.5;
        float t = clamp(dot(src - a, ab) * abInv, 0.0, 1.0);
        float z1 = eyeDepthCurrent(d1);
        float tol = 0.05 * uThickness + 2e-3 * z1;
        float lo = z1 + tol, hi = z1 + uThickness;
        float w0 = mix(iX, i0, t), w1 = mix(iX, i1, t);
        float zP0 = persp ? 1.0 / w0 : w0, zP1 = persp ? 1.0 / w1 : w1;
        // A segment that ran in front of layer 1 at the previous sample and runs behind it here, where layer 1 is
        // the same surface (no depth jump between the samples), went through it: a thin occluder that the samples
        // missed inside (a parapet seen from above).
        bool sameSurface = abs(z1 - zLast) < CROSS_MAX_JUMP * z1;
        bool cross0 = test0 && !occ0 && sameSurface && front0 && zP0 > lo;
        bool cross1 = test1 && !occ1 && sameSurface && front1 && zP1 > lo;
        front0 = zP0 < z1 - tol;
        front1 = zP1 < z1 - tol;
        zLast = z1;
        // The cheap tests first (the depth interval at the largest thickness); the second layer's depth and the
        // sample's world point only for the few samples that pass.
        bool in0 = test0 && !occ0 && zP0 > lo && zP0 < hi;
        bool in1 = test1 && !occ1 && zP1 > lo && zP1 < hi;
        if (!(in0 || in1 || cross0 || cross1)) continue;
#ifndef DEEPGI_SINGLE_LAYER
        if (twoLayers) {
            float d2 = texelFetch(uDepth, ivec3(T, 1), m).r;
            if (!isSky(d2)) {
                float hi2 = eyeDepthCurrent(d2);  // the surface's back: behind it the segment passes
                in0 = in0 && zP0 < hi2;
                in1 = in1 && zP1 < hi2;
                cross0 = cross0 && zP0 < hi2;  // behind the surface's back too: it passed behind, not through
                cross1 = cross1 && zP1 < hi2;
            }
        }
#endif
        in0 = in0 || cross0;
        in1 = in1 || cross1;
        if (!(in0 || in1)) continue;
        vec3 S = worldFromDepth(src, d1, uInvViewProj);
        float onXPlane = abs(dot(S - X, nX));
        occ0 = occ0 || (in0 && !(onXPlane < e0) && !(abs(dot(S - Y0, n0)) < e0));
        occ1 = occ1 || (in1 && !(onXPlane < e1) && !(abs(dot(S - Y1, n1)) < e1));
        if ((occ0 || !test0) && (occ1 || !test1)) break;
    }
}

// One layer of a tap: position Y, normal nY, and the contribution of its patch (irradiance, covered projected
// solid angle / pi). dA = the screen area (pixels^2) the tap stands for.
void tapLayer(int j, ivec2 T, int m, vec4 h0, vec4 hz, vec3 X, vec3 nX, float r2, float dA,
              out vec3 Y, out vec3 nY, out bool valid, out vec3 E, out float cover) {
    E = vec3(0.0);
    cover = 0.0;
    valid = false;
    nY = vec3(0.0, 0.0, 1.0);
    float dj = texelFetch(uDepth, ivec3(T, j), m).r;
    Y = X;
    if (isSky(dj)) return;
    vec4 hw = h0 + (dj * 2.0 - 1.0) * hz;
    Y = hw.xyz / hw.w;
    valid = true;
    vec3 v = Y - X;
    float vv = dot(v, v);
    if (vv <= 1e-20 * max(dot(X, X), 1e-20) || vv >= r2) return;
    vec3 wh = v * inversesqrt(vv);
    float cosX = dot(wh, nX);
    if (cosX <= 0.0) return;
    nY = octDecode(texelFetch(uNormal, ivec3(T, j), m).rg);
    float cosY = dot(-wh, nY);
    if (uTapNormalTest != 0 && cosY <= 0.0) return;
    cosY = max(cosY, 0.0);
    float a = pixelArea(Y, nY);
    // Solid angle of the patch: A * cosY / d^2, with the on-axis disk's A_texel / pi added to d^2 for the mip
    // texel's own area so that a tap next to X stays bounded (vanishing as the texel does: no bias in the limit).
    float omega = dA * a * cosY / (vv + float(1 << (2 * m)) * a / PI);
    cover = cosX * omega / PI;
    E = texelFetch(uRadiance, ivec3(T, j), m).rgb * cosX * omega;
}

#ifdef DEEPGI_PROBE_DIRECTIONAL_FILL
// Whether the screen's taps could have met the surface point Y (seen from the receiver X at pixel a): within the
// world radius and the taps' screen disk, on screen, and on a layer there (layer 1 or in front of it: the estimate
// fell short of a visible surface; or layer 2), within tol (scene units, eye depth) of it.
bool screenHolds(vec3 Y, vec3 X, vec2 a, float rss, float r2, ivec2 size, bool twoLayers, float tol) {
    vec3 v = Y - X;
    float vv = dot(v, v);
    if (vv >= r2) return false;
    if (uCameraPos.w > 0.5 && !(eyeZ(Y) > 0.0)) return false;  // behind a perspective camera
    vec2 q = toPixel(Y);
    if (any(lessThan(q, vec2(0.0))) || any(greaterThanEqual(q, vec2(size)))) return false;
    float h = length(q - a);
    if (h > rss) return false;
    int m = mipFor(h);
    ivec2 T = ivec2(q) >> m;
    float d1 = texelFetch(uDepth, ivec3(T, 0), m).r;
    if (isSky(d1)) return false;
    float zY = eyeZ(Y), tolY = tol + 0.1 * sqrt(vv);
    if (zY < eyeDepthCurrent(d1) + tolY) return true;
#ifndef DEEPGI_SINGLE_LAYER
    if (twoLayers) {
        float d2 = texelFetch(uDepth, ivec3(T, 1), m).r;
        if (!isSky(d2) && abs(zY - eyeDepthCurrent(d2)) < tolY) return true;
    }
#endif
    return false;
}
#endif

void main() {
    ivec2 pix = screenPixelOfRadiosity(ivec2(gl_FragCoord.xy));  // taps and patches in screen pixels at any grid
    float d = texelFetch(uDepth, ivec3(pix, 0), 0).r;
    if (isSky(d)) { oIrradiance = vec3(0.0); oCoverage = 0.0; return; }
    vec3 X = worldFromDepth(vec2(pix) + 0.5, d, uInvViewProj);
    vec3 nX = octDecode(texelFetch(uNormal, ivec3(pix, 0), 0).rg);
    float z = eyeDepthCurrent(d);
    float rss = uCameraPos.w > 0.5 ? uClip.z * uRadius / max(z, 1e-30) : uClip.z * uRadius;
    rss = min(rss, 4.0 * max(uViewport.x, uViewport.y));  // beyond the screen no tap finds data
    // Per-pixel rotation and radial jitter (G3D's hash), optionally varied per frame.
    float phi, jitter;
    spiralPixel(pix, gl_FragCoord.xy, uTime, phi, jitter);
    float marchJitter = fract(jitter * 7.31 + 0.5) * 0.8 + 0.1;
    ivec2 size = ivec2(uViewport.xy);
    float r2 = uRadius * uRadius;
    // worldFromDepth(p, d) = (c + p.x * cx + p.y * cy + (2d - 1) * hz).xyz / w.
    vec4 cx = uInvViewProj[0] * (2.0 * uViewport.z), cy = uInvViewProj[1] * (2.0 * uViewport.w), hz = uInvViewProj[2];
    vec4 c = uInvViewProj[3] - uInvViewProj[0] - uInvViewProj[1];
    bool twoLayers = uUseLayer2 != 0;
    float zX = eyeZ(X);
#ifdef DEEPGI_PROBES
    vec3 V = viewDirection(X);  // the probes' view bias: towards the camera, the surface's visible side
#endif
    vec3 sum = vec3(0.0);
    float covered = 0.0;
#ifdef DEEPGI_PROBE_DIRECTIONAL_FILL
    // Per sector: the covered cosine-weighted share and the taps' irradiance. The frame turns with the spiral.
    // As vec4 pairs (sectors 0-3, 4-7) added to through one-hot masks: llvmpipe turns an array indexed per pixel
    // into scattered memory accesses, 1.5 x the whole gather's time.
    vec4 coverLo = vec4(0.0), coverHi = vec4(0.0);
    vec4 redLo = vec4(0.0), redHi = vec4(0.0), greenLo = vec4(0.0), greenHi = vec4(0.0), blueLo = vec4(0.0),
         blueHi = vec4(0.0);
    vec3 ft0 = normalize(abs(nX.x) > 0.9 ? cross(nX, vec3(0.0, 1.0, 0.0)) : cross(nX, vec3(1.0, 0.0, 0.0)));
    vec3 fb0 = cross(nX, ft0);
    vec3 ft = cos(phi) * ft0 + sin(phi) * fb0, fb = cross(nX, ft);
#endif
    // Tap radii are uniform in [0, rss]: a tap at h stands for 2*pi*h*rss/N pixels^2 of the disk.
    float areaPerH = 2.0 * PI * rss / float(uNumSamples);
    for (int i = 0; i < MAX_SPIRAL_TAPS; ++i) {
        if (i >= uNumSamples) break;
        float h;
        vec2 dir = spiralTap(i, uNumSamples, uSpiralTurns, phi, jitter, rss, h);
        ivec2 Yp = pix + ivec2(h * dir);
        if (any(lessThan(Yp, ivec2(0))) || any(greaterThanEqual(Yp, size))) continue;  // off-screen: no data
        if (Yp == pix) continue;
        int m = mipFor(h);
        ivec2 T = Yp >> m;
        // The tap is the coarse texel's own sample, at the full-resolution pixel its depth came from (G3D takes
        // xy at full resolution and z from the coarse level, which puts a grazing surface's tap off the surface).
        vec2 P = vec2(sourcePixel(T, m, size)) + 0.5;
        vec4 h0 = c + P.x * cx + P.y * cy;
        float dA = areaPerH * h;
        vec3 Y0, n0, E0;
        bool v0;
        float c0;
        tapLayer(0, T, m, h0, hz, X, nX, r2, dA, Y0, n0, v0, E0, c0);
        vec3 Y1 = Y0, E1 = vec3(0.0), n1 = n0;
        float c1 = 0.0;
#ifndef DEEPGI_SINGLE_LAYER  // defined when layer 2 is off: no layer-2 code at all
        if (twoLayers && v0) {
            bool v1;
            tapLayer(1, T, m, h0, hz, X, nX, r2, dA, Y1, n1, v1, E1, c1);
            if (c1 > 0.0) {
                // Layer 2 lies behind the layer-1 surface Y0 of this pixel: X sees it only if the segment does not
                // pass through that surface where it crosses its plane (a thin wall, the pillar in front).
                float sx = dot(X - Y0, n0), sy = dot(Y1 - Y0, n0);
                if (sx > 0.0 && sy < 0.0) {
                    vec3 Q = mix(X, Y1, sx / (sx - sy));
                    ivec2 q = ivec2(toPixel(Q));
                    if (all(greaterThanEqual(q, ivec2(0))) && all(lessThan(q, size))) {
                        int mq = mipFor(length(vec2(q - pix)));
                        float dq = texelFetch(uDepth, ivec3(q >> mq, 0), mq).r;
                        if (!isSky(dq) && abs(eyeDepthCurrent(dq) - eyeZ(Q)) < uThickness + 0.02 * eyeZ(Q)) c1 = 0.0;
                    }
                }
            }
        }
#endif
        if (uVisibilitySteps > 0 && (c0 > 0.0 || c1 > 0.0)) {
            bool occ0, occ1;
            marchOccluded(vec2(pix) + 0.5, P, h, X, nX, Y0, n0, Y1, n1, zX, eyeZ(Y0), eyeZ(Y1), c0 > 0.0, c1 > 0.0,
                          marchJitter, size, twoLayers, occ0, occ1);
            if (occ0) c0 = 0.0;
            if (occ1) c1 = 0.0;
        }
#ifdef DEEPGI_PROBE_DIRECTIONAL_FILL
        for (int j = 0; j < 2; ++j) {
            float cj = j == 0 ? c0 : c1;
            if (!(cj > 0.0)) continue;
            vec3 Ej = j == 0 ? E0 : E1;
            ivec4 k = ivec4(fillSector(normalize((j == 0 ? Y0 : Y1) - X), ft, fb, nX));
            vec4 lo = vec4(equal(k, ivec4(0, 1, 2, 3))), hi = vec4(equal(k, ivec4(4, 5, 6, 7)));
            coverLo += cj * lo;
            coverHi += cj * hi;
            redLo += Ej.r * lo;
            redHi += Ej.r * hi;
            greenLo += Ej.g * lo;
            greenHi += Ej.g * hi;
            blueLo += Ej.b * lo;
            blueHi += Ej.b * hi;
        }
#else
        if (c0 > 0.0) {
            sum += E0;
            covered += c0;
        }
        if (c1 > 0.0) {
            sum += E1;
            covered += c1;
        }
#endif
    }
#ifdef DEEPGI_PROBE_DIRECTIONAL_FILL
    // Per sector: taps whose patches sum to more than the sector (their solid angles overlap: grazing patches, a
    // corner seen by both layers) are an estimate of it with too much weight, rescaled to the sector; what the taps
    // left uncovered (off screen, beyond the radius, hidden) takes the probes' radiance from a cosine-distributed
    // direction in the sector, new per pixel and frame (the blur and the temporal filter average them).
    ivec2 fillProbes[8];
    float fillWeights[8];
    vec3 fillCentre;
    bool fill = probeSetAt(X, nX, V, fillProbes, fillWeights, fillCentre);
    vec3 fillSum = vec3(0.0);
    uint seed = fillHash(uint(pix.x) * 1973u + uint(pix.y) * 9277u + floatBitsToUint(uTime) * 26699u);
    // Sectors whose taps' patches overfill them are rescaled to the sector.
    vec4 keepLo = min(vec4(1.0), SECTOR_SHARE / max(coverLo, vec4(1e-30)));
    vec4 keepHi = min(vec4(1.0), SECTOR_SHARE / max(coverHi, vec4(1e-30)));
    sum += vec3(dot(redLo, keepLo) + dot(redHi, keepHi), dot(greenLo, keepLo) + dot(greenHi, keepHi),
                dot(blueLo, keepLo) + dot(blueHi, keepHi));
    vec4 shareLo = min(coverLo, vec4(SECTOR_SHARE)), shareHi = min(coverHi, vec4(SECTOR_SHARE));
    covered = dot(shareLo, vec4(1.0)) + dot(shareHi, vec4(1.0));
    // What the taps left uncovered in a sector takes the probes' radiance from a direction the screen does not hold
    // (off screen, beyond the radius, hidden behind layer 1: screenHolds() at the probes' mean hit along it): of two
    // cosine-distributed directions in the sector, the first that it does not hold, else the second. Radiance from
    // any direction of the sector (the fill before) counted a bright patch twice where the taps had found it, and
    // brought the dark of its surroundings where they had not (sun patch room, one bounce: 20 % bright at radius 0.6,
    // 6 % dark at 0.3). Where the radiance is the same everywhere (the closed furnace) the choice changes nothing.
    float holdTol = 0.5 * min(uProbeSpacing.x, min(uProbeSpacing.y, uProbeSpacing.z));
    for (int k = 0; k < FILL_SECTORS; ++k) {
        float share = k < 4 ? shareLo[k] : shareHi[k - 4];
        if (fill && share < SECTOR_SHARE) {
            uint h1 = fillHash(seed + uint(k) * 0x9e3779b9u), h2 = fillHash(h1);
            vec3 dir = sectorDirection(k, vec2(float(h1 >> 8), float(h2 >> 8)) * (1.0 / 16777216.0), ft, fb, nX);
            vec4 Lt = probeRadianceDistanceAt(fillProbes, fillWeights, dir);
            // Its light comes from the probes' mean hit: their mean position plus the texel's mean distance along
            // the texel's centre (not along dir at its edge: a floor met at a grazing angle, 1/cos convex across the
            // texel, put the point far under it; nor moved onto X's own ray, which puts it off such a floor).
            vec3 texelDir = octDecode((vec2(probeRadianceTexel(dir)) + 0.5) / float(uProbeTexels.w) * 2.0 - 1.0);
            vec3 L = Lt.rgb;
            if (screenHolds(fillCentre + Lt.a * texelDir, X, vec2(pix) + 0.5, rss, r2, size, twoLayers, holdTol)) {
                uint h3 = fillHash(h2), h4 = fillHash(h3);
                vec2 u = vec2(float(h3 >> 8), float(h4 >> 8)) * (1.0 / 16777216.0);
                L = probeRadianceAt(fillProbes, fillWeights, sectorDirection(k, u, ft, fb, nX));
            }
            fillSum += (PI * (SECTOR_SHARE - share)) * L;
        }
    }
    // Bounded by the probes' irradiance, their own estimate of the whole hemisphere: a coarse radiance texel that
    // straddles a surface's horizon must not bring the light below it from above. The bound is 2 x that mean, not
    // 1 x: the sum of one sample per sector is noisy, and clamping a noisy estimate at its mean would darken it.
    if (fill) sum += min(fillSum, 2.0 * probeIrradianceAt(fillProbes, fillWeights, nX));
#endif
    covered = clamp(covered, 0.0, 1.0);
#if defined(DEEPGI_PROBES) && !defined(DEEPGI_PROBE_DIRECTIONAL_FILL)
    // The directions the screen did not cover (off screen, beyond the radius, hidden) take the probes' light.
    sum += (1.0 - covered) * probeIrradiance(X, nX, V);
#endif
    oIrradiance = sanitizeR11G11B10(sum, gl_FragCoord.xy);
    oCoverage = covered;
}
