// The viewer's dynamic resolution (see the header for the rules).
#include "app/dynamic_resolution.h"

#include <algorithm>
#include <cmath>
#include <vector>

namespace deepgi {

namespace {

double median(const std::deque<FrameSample>& s, double FrameSample::*field, size_t lastN) {
    std::vector<double> v;
    for (size_t i = s.size() > lastN ? s.size() - lastN : 0; i < s.size(); ++i) v.push_back(s[i].*field);
    if (v.empty()) return 0.0;
    std::nth_element(v.begin(), v.begin() + long(v.size() / 2), v.end());
    return v[v.size() / 2];
}

}  // namespace

void DynamicResolution::setStep(int s) {
    s = std::clamp(s, kMinStep, kSteps);
    if (s == step_) return;
    step_ = s;
    samples_.clear();
    skip_ = 1;
}

int DynamicResolution::predict(double frameMs, double renderMs, int atStep) const {
    // The render's cost goes with the pixel count (the scale squared); the rest of the frame (UI, swap) stays.
    const double budget = target_ * 0.95 - std::max(frameMs - renderMs, 0.0);
    if (budget <= 0.0) return kMinStep;
    const double scale = double(atStep) / kSteps * std::sqrt(budget / std::max(renderMs, 1e-3));
    return std::clamp(int(std::floor(scale * kSteps + 1e-9)), kMinStep, kSteps);
}

int DynamicResolution::next(bool moving, const FrameSample& last) {
    if (!enabled()) {
        setStep(kSteps);
        wasMoving_ = false;
        return step_;
    }
    if (last.valid && last.step == step_) {
        if (skip_ > 0) --skip_;
        else {
            samples_.push_back(last);
            if (samples_.size() > 12) samples_.pop_front();
        }
    }
    if (step_ == kSteps && !wasMoving_ && !samples_.empty()) {
        haveFull_ = true;
        fullFrameMs_ = median(samples_, &FrameSample::frameMs, 5);
        fullRenderMs_ = median(samples_, &FrameSample::renderMs, 5);
    }
    if (!moving) {
        if (wasMoving_) movingStep_ = step_;
        wasMoving_ = false;
        setStep(kSteps);  // still: the whole viewport, kept while still
        return step_;
    }
    if (!wasMoving_) {  // a motion starts: at the size the still frames predict, else where the last one ended
        wasMoving_ = true;
        setStep(haveFull_ ? predict(fullFrameMs_, fullRenderMs_, kSteps) : movingStep_ > 0 ? movingStep_ : kSteps);
        return step_;
    }
    if (samples_.size() >= 2) {
        const double a = samples_[samples_.size() - 1].frameMs, b = samples_[samples_.size() - 2].frameMs;
        const bool spike = std::min(a, b) > kOver * target_;
        // A size whose frames sit just over the target does not hold it: six frames' median over it steps down too.
        const bool over = samples_.size() >= 6 && median(samples_, &FrameSample::frameMs, 6) > target_;
        if ((spike || over) && step_ > kMinStep) {
            const size_t n = spike ? 3 : 6;
            const double frame = median(samples_, &FrameSample::frameMs, n), render = median(samples_, &FrameSample::renderMs, n);
            setStep(std::min(step_ - 1, predict(frame, render, step_)));
        } else if (samples_.size() >= 6 && step_ < kSteps) {
            const double frame = median(samples_, &FrameSample::frameMs, 6), render = median(samples_, &FrameSample::renderMs, 6);
            const double up = double(step_ + 1) / double(step_);
            if (frame < kUnder * target_ && frame - render + render * up * up < kUpMargin * target_) setStep(step_ + 1);
        }
    }
    return step_;
}

}  // namespace deepgi
