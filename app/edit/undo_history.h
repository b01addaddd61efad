#pragma once
// The viewer's undo and redo (Ctrl+Z / Shift+Ctrl+Z): a bounded list of steps, each the edited state before and
// after one edit (whole snapshots: exact to restore, and the scene's edit state is small next to its meshes).
// A new edit after some undos drops the steps that could have been redone, as Blender does.
#include <cstddef>
#include <deque>
#include <string>
#include <utility>

namespace deepgi::edit {

template <class State>
class UndoHistory {
public:
    explicit UndoHistory(size_t maxSteps = 64) : maxSteps_(maxSteps < 1 ? 1 : maxSteps) {}

    // One edit: what it changed from and to. A step that changes nothing is not recorded (returns false).
    bool push(std::string label, State before, State after) {
        if (before == after) return false;
        steps_.erase(steps_.begin() + std::ptrdiff_t(done_), steps_.end());
        steps_.push_back({std::move(label), std::move(before), std::move(after)});
        if (steps_.size() > maxSteps_) steps_.pop_front();
        done_ = steps_.size();
        return true;
    }
    bool canUndo() const { return done_ > 0; }
    bool canRedo() const { return done_ < steps_.size(); }
    // The state to go back to (nullptr: nothing to undo); `label` gets the edit's name.
    const State* undo(std::string* label = nullptr) {
        if (!canUndo()) return nullptr;
        const Step& s = steps_[--done_];
        if (label) *label = s.label;
        return &s.before;
    }
    const State* redo(std::string* label = nullptr) {
        if (!canRedo()) return nullptr;
        const Step& s = steps_[done_++];
        if (label) *label = s.label;
        return &s.after;
    }
    size_t size() const { return steps_.size(); }
    size_t undoable() const { return done_; }
    // Labels, oldest first, and how many of them are done (the rest can be redone): for the UI's history list.
    std::deque<std::string> labels() const {
        std::deque<std::string> l;
        for (const auto& s : steps_) l.push_back(s.label);
        return l;
    }
    void clear() { steps_.clear(), done_ = 0; }

private:
    struct Step {
        std::string label;
        State before, after;
    };
    std::deque<Step> steps_;
    size_t done_ = 0;  // steps_[0, done_) are applied
    size_t maxSteps_;
};

}  // namespace deepgi::edit
