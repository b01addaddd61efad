#include "renderer/scene/environment_map.h"

#include "renderer/core/image_io.h"
#include "renderer/scene/scene.h"

#include <OpenImageIO/imagebuf.h>
#include <OpenImageIO/imagebufalgo.h>
#include <OpenImageIO/imageio.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace deepgi {
namespace {

constexpr float kPi = 3.14159265358979323846f;

float luminance(const glm::vec3& c) { return 0.2126f * c.x + 0.7152f * c.y + 0.0722f * c.z; }

// Index of the interval [cdf[i], cdf[i+1]) holding u (cdf ascending from 0 to 1, n + 1 entries), skipping empty ones.
int findInterval(const float* cdf, int n, float u) {
    const float* it = std::upper_bound(cdf, cdf + n + 1, u);
    int i = int(it - cdf) - 1;
    i = std::clamp(i, 0, n - 1);
    while (i > 0 && !(cdf[i + 1] > cdf[i])) --i;       // u at 1 (rounding) lands past the last non-empty one
    while (i < n - 1 && !(cdf[i + 1] > cdf[i])) ++i;
    return i;
}

}  // namespace

EnvironmentMap makeEnvironmentMap(int width, int height, std::vector<float> rgb, const std::string& name) {
    if (width <= 0 || height <= 0 || rgb.size() != size_t(width) * size_t(height) * 3)
        throw std::runtime_error(name + ": environment map has no pixels (" + std::to_string(width) + "x" +
                                 std::to_string(height) + ")");
    size_t bad = 0, firstBad = 0;
    for (size_t i = 0; i < rgb.size(); ++i)
        if (!std::isfinite(rgb[i]) || rgb[i] < 0.0f) {
            if (bad++ == 0) firstBad = i / 3;
        }
    if (bad) {
        const size_t x = firstBad % size_t(width), y = firstBad / size_t(width);
        throw std::runtime_error(name + ": environment map has " + std::to_string(bad) +
                                 " non-finite or negative channel values (first at pixel " + std::to_string(x) + ", " +
                                 std::to_string(y) + " from the top); radiance must be finite and >= 0");
    }
    EnvironmentMap m;
    m.path = name;
    m.width = width;
    m.height = height;
    m.rgb = std::move(rgb);
    if (width != 2 * height)
        m.warnings.push_back(name + ": environment map is " + std::to_string(width) + "x" + std::to_string(height) +
                             ", not 2:1; it is still mapped over the whole sphere (equirectangular)");
    return m;
}

EnvironmentMap loadEnvironmentMap(const std::string& path) {
    auto in = OIIO::ImageInput::open(path);
    if (!in) {
        std::string why = OIIO::geterror();
        if (why.empty()) why = "not an image OpenImageIO can read";
        throw std::runtime_error(path + ": cannot read the environment map: " + why);
    }
    const OIIO::ImageSpec spec = in->spec();
    const int w = spec.width, h = spec.height, nch = spec.nchannels;
    if (w <= 0 || h <= 0 || nch <= 0)
        throw std::runtime_error(path + ": environment map has no pixels (" + std::to_string(w) + "x" +
                                 std::to_string(h) + ", " + std::to_string(nch) + " channels)");
    if (int64_t(w) * h > int64_t(1) << 28)
        throw std::runtime_error(path + ": environment map of " + std::to_string(w) + "x" + std::to_string(h) +
                                 " is too large (at most 2^28 pixels)");
    std::vector<float> px(size_t(w) * h * nch);
    if (!in->read_image(0, 0, 0, nch, OIIO::TypeDesc::FLOAT, px.data())) {
        std::string why = in->geterror();
        throw std::runtime_error(path + ": cannot read the environment map's pixels: " + (why.empty() ? "read failed" : why));
    }
    in->close();
    // Integer formats (PNG, JPEG, ...) hold sRGB-encoded values unless the file says linear.
    const std::string colorSpace = spec.get_string_attribute("oiio:ColorSpace");
    const bool integer = !spec.format.is_floating_point();
    const bool linear = colorSpace.find("inear") != std::string::npos || colorSpace.find("lin_") == 0;
    const bool decodeSrgb = integer && !linear;
    std::vector<std::string> notes;
    if (integer)
        notes.push_back(path + ": environment map is " + std::to_string(spec.format.size() * 8) +
                        "-bit (no high dynamic range: a sun in it is clipped)" +
                        (decodeSrgb ? "; decoded from sRGB" : ""));
    std::vector<float> rgb(size_t(w) * h * 3);
    for (size_t i = 0; i < size_t(w) * h; ++i)
        for (int c = 0; c < 3; ++c) {
            // 1 channel: grey; 2: grey + alpha; 3 or more: RGB (alpha and others ignored).
            const int src = nch >= 3 ? c : 0;
            float v = px[i * nch + src];
            if (decodeSrgb) v = srgbToLinear(v);
            rgb[i * 3 + c] = v;
        }
    px.clear();
    px.shrink_to_fit();
    int outW = w, outH = h;
    if (w > kMaxEnvironmentWidth) {
        outW = kMaxEnvironmentWidth;
        outH = std::max(1, int(int64_t(h) * kMaxEnvironmentWidth / w));
        OIIO::ImageBuf src(OIIO::ImageSpec(w, h, 3, OIIO::TypeDesc::FLOAT), rgb.data());
        OIIO::ImageBuf dst(OIIO::ImageSpec(outW, outH, 3, OIIO::TypeDesc::FLOAT));
        if (!OIIO::ImageBufAlgo::resample(dst, src, true))
            throw std::runtime_error(path + ": cannot downscale the environment map: " + dst.geterror());
        std::vector<float> small(size_t(outW) * outH * 3);
        dst.get_pixels(OIIO::ROI(0, outW, 0, outH, 0, 1, 0, 3), OIIO::TypeDesc::FLOAT, small.data());
        rgb.swap(small);
        notes.push_back(path + ": environment map of " + std::to_string(w) + "x" + std::to_string(h) +
                        " downscaled to " + std::to_string(outW) + "x" + std::to_string(outH) +
                        " (at most " + std::to_string(kMaxEnvironmentWidth) + " wide)");
    }
    EnvironmentMap m = makeEnvironmentMap(outW, outH, std::move(rgb), path);
    m.warnings.insert(m.warnings.begin(), notes.begin(), notes.end());
    return m;
}

void attachEnvironment(Scene& scene, const std::string& path) {
    if (path.empty()) return;
    auto map = std::make_shared<EnvironmentMap>(loadEnvironmentMap(path));
    scene.warnings.insert(scene.warnings.end(), map->warnings.begin(), map->warnings.end());
    scene.environment = std::move(map);
}

glm::vec2 equirectFromDirection(const glm::vec3& d) {
    float u = 0.5f + std::atan2(d.z, d.x) * (0.5f / kPi);
    if (!(u < 1.0f)) u = 0.0f;  // atan2 = pi exactly wraps to the left edge
    const float t = std::acos(std::clamp(d.y, -1.0f, 1.0f)) / kPi;
    return {u, t};
}

glm::vec3 directionFromEquirect(float u, float t) {
    const float phi = (u - 0.5f) * 2.0f * kPi, theta = t * kPi;
    const float s = std::sin(theta);
    return {s * std::cos(phi), std::cos(theta), s * std::sin(phi)};
}

bool environmentOn(const Scene& scene, const Settings& s) {
    return s.environmentIntensity > 0.0f && (s.skyRadiance > 0.0f || scene.environment != nullptr);
}

EnvironmentLight::EnvironmentLight(const EnvironmentMap* map, const Settings& s, bool withSampling)
    : map_(map && map->width > 0 && map->height > 0 ? map : nullptr),
      sky_(std::max(0.0f, s.skyRadiance)),
      intensity_(std::max(0.0f, s.environmentIntensity)),
      cosRotation_(std::cos(glm::radians(s.environmentRotation))),
      sinRotation_(std::sin(glm::radians(s.environmentRotation))) {
    bool any = sky_ > 0.0f;
    if (map_ && !any)
        for (float v : map_->rgb)
            if (v > 0.0f) { any = true; break; }
    enabled_ = intensity_ > 0.0f && any;
    if (!withSampling || !enabled_ || !map_) return;
    const int W = map_->width, H = map_->height;
    std::vector<float> lum(size_t(W) * H);
    for (int y = 0; y < H; ++y)
        for (int x = 0; x < W; ++x) lum[size_t(y) * W + x] = luminance(texel(x, y)) + sky_;
    std::vector<float> weight(size_t(W) * H);
    for (int y = 0; y < H; ++y) {
        const float sinTheta = std::sin((float(y) + 0.5f) / float(H) * kPi);
        for (int x = 0; x < W; ++x) {
            float m = 0.0f;
            for (int dy = -1; dy <= 1; ++dy)
                for (int dx = -1; dx <= 1; ++dx) {
                    const int yy = std::clamp(y + dy, 0, H - 1), xx = ((x + dx) % W + W) % W;
                    m = std::max(m, lum[size_t(yy) * W + xx]);
                }
            // A neighbour's bilinear share averages about 1/8 over a texel: a quarter of the neighbourhood's
            // largest keeps the density positive where the lookup is, without spreading a sun over 9 texels.
            weight[size_t(y) * W + x] = std::max(lum[size_t(y) * W + x], 0.25f * m) * sinTheta;
        }
    }
    conditionalCdf_.assign(size_t(H) * (W + 1), 0.0f);
    std::vector<double> rowSum(size_t(H), 0.0);
    double total = 0.0;
    for (int y = 0; y < H; ++y) {
        double acc = 0.0;
        float* cdf = &conditionalCdf_[size_t(y) * (W + 1)];
        for (int x = 0; x < W; ++x) {
            acc += weight[size_t(y) * W + x];
            cdf[x + 1] = float(acc);
        }
        rowSum[y] = acc;
        total += acc;
        for (int x = 1; x <= W; ++x) cdf[x] = acc > 0.0 ? float(cdf[x] / acc) : float(x) / float(W);
        cdf[W] = 1.0f;
    }
    if (!(total > 0.0)) {  // radiance zero everywhere but within the bleed of nothing: cannot happen with enabled_
        conditionalCdf_.clear();
        return;
    }
    marginalCdf_.assign(size_t(H) + 1, 0.0f);
    rowWeight_.assign(size_t(H), 0.0f);
    double acc = 0.0;
    for (int y = 0; y < H; ++y) {
        acc += rowSum[y];
        marginalCdf_[y + 1] = float(acc / total);
        rowWeight_[y] = float(rowSum[y] / total);
    }
    marginalCdf_[H] = 1.0f;
    texelProbability_.assign(size_t(W) * H, 0.0f);
    for (size_t i = 0; i < texelProbability_.size(); ++i) texelProbability_[i] = float(weight[i] / total);
}

glm::vec3 EnvironmentLight::texel(int x, int y) const {
    const float* p = &map_->rgb[(size_t(y) * map_->width + x) * 3];
    return {p[0], p[1], p[2]};
}

glm::vec3 EnvironmentLight::toMap(const glm::vec3& d) const {
    return {d.x * cosRotation_ - d.z * sinRotation_, d.y, d.x * sinRotation_ + d.z * cosRotation_};
}

glm::vec3 EnvironmentLight::fromMap(const glm::vec3& m) const {
    return {m.x * cosRotation_ + m.z * sinRotation_, m.y, -m.x * sinRotation_ + m.z * cosRotation_};
}

glm::vec3 EnvironmentLight::radiance(const glm::vec3& d) const {
    if (!enabled_) return glm::vec3(0.0f);
    glm::vec3 L(sky_);
    if (map_) {
        const glm::vec2 ut = equirectFromDirection(toMap(d));
        const int W = map_->width, H = map_->height;
        const float fx = ut.x * float(W) - 0.5f, fy = ut.y * float(H) - 0.5f;
        const float x0f = std::floor(fx), y0f = std::floor(fy), tx = fx - x0f, ty = fy - y0f;
        const int x0 = ((int(x0f) % W) + W) % W, x1 = (x0 + 1) % W;
        const int y0 = std::clamp(int(y0f), 0, H - 1), y1 = std::clamp(int(y0f) + 1, 0, H - 1);
        L += glm::mix(glm::mix(texel(x0, y0), texel(x1, y0), tx), glm::mix(texel(x0, y1), texel(x1, y1), tx), ty);
    }
    return intensity_ * L;
}

EnvironmentLight::Sample EnvironmentLight::sample(float u1, float u2) const {
    Sample s;
    if (!sampled()) return s;
    const int W = map_->width, H = map_->height;
    const int y = findInterval(marginalCdf_.data(), H, u1);
    const float rowLo = marginalCdf_[y], rowP = rowWeight_[y];
    const float fy = rowP > 0.0f ? std::clamp((u1 - rowLo) / rowP, 0.0f, 0.99999994f) : 0.5f;
    const float* cdf = &conditionalCdf_[size_t(y) * (W + 1)];
    const int x = findInterval(cdf, W, u2);
    const float colP = cdf[x + 1] - cdf[x];
    const float fx = colP > 0.0f ? std::clamp((u2 - cdf[x]) / colP, 0.0f, 0.99999994f) : 0.5f;
    const float u = (float(x) + fx) / float(W), t = (float(y) + fy) / float(H);
    s.direction = fromMap(directionFromEquirect(u, t));
    const float sinTheta = std::sin(t * kPi);
    const float p = texelProbability_[size_t(y) * W + x];
    // Uniform within the texel in (u, t): density W*H*p over the unit square, / (2 pi^2 sin(theta)) per solid angle.
    s.pdf = sinTheta > 0.0f ? p * float(W) * float(H) / (2.0f * kPi * kPi * sinTheta) : 0.0f;
    s.radiance = radiance(s.direction);
    return s;
}

float EnvironmentLight::pdf(const glm::vec3& d) const {
    if (!sampled()) return 0.0f;
    const int W = map_->width, H = map_->height;
    const glm::vec2 ut = equirectFromDirection(toMap(d));
    const int x = std::clamp(int(ut.x * float(W)), 0, W - 1), y = std::clamp(int(ut.y * float(H)), 0, H - 1);
    const float sinTheta = std::sin(ut.y * kPi);
    if (!(sinTheta > 0.0f)) return 0.0f;
    return texelProbability_[size_t(y) * W + x] * float(W) * float(H) / (2.0f * kPi * kPi * sinTheta);
}

}  // namespace deepgi
