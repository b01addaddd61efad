#pragma once
// "Path trace this view": the reference path tracer renders the viewer's camera progressively on a worker thread
// (1 sample per pixel per pass with a new seed each pass, accumulated), at a reduced resolution and on all cores
// but one, so the viewer stays usable. A new camera, light setting or size restarts the accumulation.
#include "renderer/core/camera.h"
#include "renderer/core/image_io.h"
#include "renderer/core/settings.h"
#include "renderer/scene/scene.h"

#include <atomic>
#include <condition_variable>
#include <memory>
#include <mutex>
#include <string>
#include <thread>

namespace deepgi {

class ViewerPathTrace {
public:
    // threads 0 = hardware_concurrency - 1 (at least 1).
    ViewerPathTrace(std::shared_ptr<const Scene> scene, int threads = 0, int maxBounces = 16);
    ~ViewerPathTrace();  // stops the worker (waits for its current pass)

    // The view to trace; a change of camera, size or a setting the path tracer reads (the Light group) restarts the
    // accumulation. Cheap when unchanged.
    void request(const Camera& camera, const Settings& settings, int width, int height);
    void pause();  // stops tracing until the next request()

    struct Snapshot {
        FloatImage final, direct;  // mean of the passes so far (RGB linear)
        int samples = 0;           // samples per pixel accumulated
        uint64_t generation = 0;   // bumps on every restart
        double seconds = 0.0;      // tracing time of this accumulation
    };
    // The latest accumulation if it changed since `sinceSamples`/`sinceGeneration`; false otherwise.
    bool latest(Snapshot& out, int sinceSamples, uint64_t sinceGeneration) const;
    std::string status() const;  // "building the BVH", "12 spp, 1.3 s, 3 threads", or an error
    int threads() const { return threads_; }

private:
    void work();

    std::shared_ptr<const Scene> scene_;
    int threads_, maxBounces_;
    mutable std::mutex mutex_;
    std::condition_variable wake_;
    bool stop_ = false, active_ = false;
    Camera camera_;
    std::string settingsKey_;
    Settings settings_;
    int width_ = 0, height_ = 0;
    uint64_t generation_ = 0;
    Snapshot result_;
    std::string status_ = "starting";
    std::thread worker_;
};

}  // namespace deepgi
