#pragma once
// The viewer's dynamic resolution: while the camera moves, the render size is a fraction of the viewport (steps of
// 1/8 from 1/4 to 1) chosen from the measured frame times against a target frame time; when the camera is still
// it is the whole viewport. Plain logic (no GL, no window): the viewer feeds it each frame's times.
// A new render size invalidates the renderer's temporal history, so it changes rarely: two frames 15 % over the
// target, or six whose median is over it, step down (to the size predicted to hold it), six frames well under it step
// up by one, and a motion starts at the size predicted from the still frames.
#include <deque>

namespace deepgi {

struct FrameSample {
    double frameMs = 0.0;   // the whole frame: input, render, UI, swap
    double renderMs = 0.0;  // the renderer's part of it
    int step = 0;           // the scale it ran at, in eighths
    bool valid = false;     // false: a frame not to learn from (a resize, `converge`, a capture, the first one)
};

class DynamicResolution {
public:
    static constexpr int kSteps = 8;    // scale = step / kSteps
    static constexpr int kMinStep = 2;  // 1/4 of the viewport's width and height
    static constexpr double kOver = 1.15, kUnder = 0.75, kUpMargin = 0.9;

    // ms <= 0 turns it off (always full size).
    void setTarget(double ms) { target_ = ms; }
    double target() const { return target_; }
    bool enabled() const { return target_ > 0.0; }
    // The step for the next frame, from whether the camera is moving and the previous frame's times.
    int next(bool moving, const FrameSample& last);
    int step() const { return step_; }
    double scale() const { return double(step_) / kSteps; }

private:
    void setStep(int s);
    int predict(double frameMs, double renderMs, int atStep) const;  // the largest step expected to hold the target
    double target_ = 0.0;
    int step_ = kSteps;
    int movingStep_ = -1;             // the step the last motion ended at (-1: none yet)
    bool wasMoving_ = false;
    int skip_ = 1;                    // frames at a new size not to learn from (allocation, first-frame costs)
    std::deque<FrameSample> samples_;  // at step_, since it was chosen
    bool haveFull_ = false;           // the median of the last still frames at full size
    double fullFrameMs_ = 0.0, fullRenderMs_ = 0.0;
};

}  // namespace deepgi
