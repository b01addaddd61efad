#include "app/viewer_path_trace.h"

#include "renderer/reference/path_tracer.h"


#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstring>

namespace deepgi {

ViewerPathTrace::ViewerPathTrace(std::shared_ptr<const Scene> scene, int threads, int maxBounces)
    : scene_(std::move(scene)),
      threads_(threads > 0 ? threads : std::max(1, int(std::thread::hardware_concurrency()) - 1)),
      maxBounces_(maxBounces) {
    worker_ = std::thread([this] { work(); });
}

ViewerPathTrace::~ViewerPathTrace() {
    {
        std::lock_guard<std::mutex> lock(mutex_);
        stop_ = true;
    }
    wake_.notify_all();
    worker_.join();
}

void ViewerPathTrace::request(const Camera& camera, const Settings& settings, int width, int height) {
    // The path tracer reads only the lights and the backdrop (the Light group): other settings do not restart it.
    std::string key;
    for (const auto& info : settingTable())
        if (std::string(info.key).rfind("light.", 0) == 0) {
            char v[32];
            std::snprintf(v, sizeof(v), "%.17g,", info.get(settings));
            key += v;
        }
    std::lock_guard<std::mutex> lock(mutex_);
    const bool same = active_ && width == width_ && height == height_ && key == settingsKey_ &&
                      std::memcmp(&camera.cameraToWorld, &camera_.cameraToWorld, sizeof(glm::mat4)) == 0 &&
                      camera.perspective == camera_.perspective && camera.yfov == camera_.yfov &&
                      camera.orthoHalfHeight == camera_.orthoHalfHeight;
    if (same) return;
    camera_ = camera;
    settings_ = settings;
    settingsKey_ = key;
    width_ = width;
    height_ = height;
    active_ = true;
    ++generation_;
    wake_.notify_all();
}

void ViewerPathTrace::pause() {
    std::lock_guard<std::mutex> lock(mutex_);
    active_ = false;
}

bool ViewerPathTrace::latest(Snapshot& out, int sinceSamples, uint64_t sinceGeneration) const {
    std::lock_guard<std::mutex> lock(mutex_);
    if (result_.samples == 0 || (result_.samples == sinceSamples && result_.generation == sinceGeneration)) return false;
    out = result_;
    return true;
}

std::string ViewerPathTrace::status() const {
    std::lock_guard<std::mutex> lock(mutex_);
    return status_;
}

void ViewerPathTrace::work() {
    std::unique_ptr<ReferenceTracer> tracer;
    FloatImage sumFinal, sumDirect;
    int samples = 0;
    uint64_t gen = 0;
    double seconds = 0.0;
    for (;;) {
        Camera cam;
        Settings settings;
        int w = 0, h = 0;
        {
            std::unique_lock<std::mutex> lock(mutex_);
            wake_.wait(lock, [&] { return stop_ || active_; });
            if (stop_) return;
            cam = camera_;
            settings = settings_;
            w = width_;
            h = height_;
            if (gen != generation_) {  // restart
                gen = generation_;
                samples = 0;
                seconds = 0.0;
                result_ = Snapshot{};
                result_.generation = gen;
            }
            if (!tracer) status_ = "building the BVH";
        }
        try {
            if (!tracer) tracer = std::make_unique<ReferenceTracer>(*scene_);
            if (samples == 0) {
                sumFinal = FloatImage{w, h, 3, std::vector<float>(size_t(w) * h * 3, 0.0f)};
                sumDirect = sumFinal;
            }
            // A few samples per pass once the first has shown something: fewer thread start-ups per sample.
            ReferenceOptions o;
            o.width = w;
            o.height = h;
            o.spp = std::min(1 << std::min(samples, 3), 8);
            o.maxBounces = maxBounces_;
            o.seed = uint64_t(samples) * 7919u + 1u;  // a new, reproducible seed per pass
            o.threads = threads_;
            o.progress = false;
            const auto t0 = std::chrono::steady_clock::now();
            const ReferenceResult r = tracer->render(cam, settings, o);
            seconds += std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
            for (size_t i = 0; i < sumFinal.pixels.size(); ++i) {
                sumFinal.pixels[i] += r.final.pixels[i] * float(o.spp);
                sumDirect.pixels[i] += r.direct.pixels[i] * float(o.spp);
            }
            samples += o.spp;
            std::lock_guard<std::mutex> lock(mutex_);
            if (gen != generation_ || stop_) continue;  // restarted meanwhile: throw this pass away
            result_.final = sumFinal;
            result_.direct = sumDirect;
            const float inv = 1.0f / float(samples);
            for (auto& v : result_.final.pixels) v *= inv;
            for (auto& v : result_.direct.pixels) v *= inv;
            result_.samples = samples;
            result_.generation = gen;
            result_.seconds = seconds;
            char buf[128];
            std::snprintf(buf, sizeof(buf), "%d spp, %.1f s, %dx%d, %d thread%s", samples, seconds, w, h, threads_,
                          threads_ == 1 ? "" : "s");
            status_ = buf;
            if (samples >= 1 << 16) active_ = false;  // converged far enough: stop using the cores
        } catch (const std::exception& e) {
            std::lock_guard<std::mutex> lock(mutex_);
            status_ = std::string("path tracer failed: ") + e.what();
            active_ = false;
        }
    }
}

}  // namespace deepgi
