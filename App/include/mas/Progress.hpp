// How a long engine computation (decomposing a part, slicing it) tells its caller how far it is,
// and how the caller stops it.
#pragma once

#include <functional>
#include <memory>
#include <string>

namespace mas {

// A handle the engine reports through. The caller gives a Report, called with the fraction of the
// whole computation done so far (0 to 1, never decreasing from one call to the next; 1 when done)
// and the stage that runs, in words ("slicing component 2 (3 of 5)"). The engine calls it now and
// then (between layers, candidate planes, components, splits), always from the thread that called
// the engine, never from a worker thread: a GUI may repaint from it. The Report may throw to stop
// the work (mas::Error with ErrorCode::Cancelled, or any exception of the caller's own): the
// exception leaves the engine call unchanged, and nothing the caller passed is modified.
//
// A default-constructed Progress reports nothing and never stops. span() gives a stage its share of
// the whole, so that a function reports 0 to 1 of its own work without knowing its caller's.
class Progress {
public:
    using Report = std::function<void(double fraction, const std::string& stage)>;

    Progress() = default;
    explicit Progress(Report report);

    // Reports `done` (0 to 1, clamped) of this span's work, under its stage.
    void operator()(double done) const;
    // Reports no new fraction: a point where the caller may stop the work.
    void check() const;
    // The share [lo, hi] (fractions of this span) of this span, under `stage` (empty: this span's).
    Progress span(double lo, double hi, std::string stage = {}) const;

    explicit operator bool() const { return static_cast<bool>(state_); }

private:
    struct State {
        Report report;
        double last = 0.0;  // the highest fraction reported
    };
    std::shared_ptr<State> state_;
    double lo_ = 0.0, hi_ = 1.0;
    std::string stage_;
};

}  // namespace mas
