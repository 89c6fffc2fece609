#include "mas/Progress.hpp"

#include <algorithm>
#include <cmath>
#include <utility>

namespace mas {

Progress::Progress(Report report) {
    if (report) state_ = std::make_shared<State>(State{std::move(report), 0.0});
}

void Progress::operator()(double done) const {
    if (!state_) return;
    // NaN counts as nothing done. span() keeps lo_ <= hi_ within [0, 1].
    const double d = std::isnan(done) ? 0.0 : std::clamp(done, 0.0, 1.0);
    state_->last = std::max(state_->last, lo_ + d * (hi_ - lo_));
    state_->report(state_->last, stage_);
}

void Progress::check() const {
    if (!state_) return;
    state_->report(state_->last, stage_);
}

Progress Progress::span(double lo, double hi, std::string stage) const {
    Progress out = *this;
    const double w = hi_ - lo_;
    lo = std::clamp(lo, 0.0, 1.0);
    hi = std::clamp(hi, lo, 1.0);
    out.lo_ = lo_ + lo * w;
    out.hi_ = lo_ + hi * w;
    if (!stage.empty()) out.stage_ = std::move(stage);
    return out;
}

}  // namespace mas
