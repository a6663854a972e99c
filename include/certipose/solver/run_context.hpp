// certipose/solver/run_context.hpp — the clock, deadline and cancellation of one run, shared by
// the stages that make it: pose_solver's stages for one facet, the part scheduler for a whole
// part (part/scheduler.hpp), and user code that assembles stages itself.
//
//   certipose::run_context run(options.stop, std::chrono::seconds(30));
//   stage.pave(popt, run.token());               // one token for the user's stop and our own
//   if (run.out_of_time()) ...;                  // cancelled or past the deadline
//   run.stop(certipose::termination::box_budget);  // the first reason given is the run's
//
// It holds a stop source of its own, linked to the user's token: stopping the run for a budget
// does not touch the caller's token, and a stop of the caller's token stops every stage that
// holds `token()`. Not copyable or movable: stages hold references to it.
#pragma once

#include <atomic>
#include <chrono>
#include <optional>
#include <stop_token>

#include "certipose/outcome.hpp"  // termination

namespace certipose {

/// The clock, deadline and cancellation of one run (see the header comment).
class run_context {
public:
    using clock = std::chrono::steady_clock;

    /// A run that the caller's `stop` cancels and that ends `time_limit` after now.
    explicit run_context(std::stop_token stop = {}, std::optional<clock::duration> time_limit = std::nullopt)
        : start_(clock::now()), forward_(std::move(stop), forwarder{&halt_}) {
        if (time_limit) deadline_ = start_ + *time_limit;
    }
    run_context(const run_context&) = delete;
    run_context& operator=(const run_context&) = delete;

    clock::time_point start() const noexcept { return start_; }
    std::optional<clock::time_point> deadline() const noexcept { return deadline_; }
    /// Seconds since the run started.
    double seconds() const { return std::chrono::duration<double>(clock::now() - start_).count(); }
    bool past_deadline() const { return deadline_ && clock::now() >= *deadline_; }

    /// Requested when the caller's token is, or `stop` is called.
    std::stop_token token() const noexcept { return halt_.get_token(); }
    bool stop_requested() const noexcept { return halt_.stop_requested(); }
    /// Cancelled, stopped, or past the deadline.
    bool out_of_time() const { return stop_requested() || past_deadline(); }

    /// Stops the run for `why`; the first reason given is kept.
    void stop(termination why) noexcept {
        int expected = none;
        why_.compare_exchange_strong(expected, static_cast<int>(why));
        halt_.request_stop();
    }
    /// Why the run stopped: the first `stop`'s reason; `cancelled` when only the caller's token
    /// stopped it; `completed` when nothing did.
    termination reason() const noexcept {
        const int why = why_.load();
        if (why != none) return static_cast<termination>(why);
        return halt_.stop_requested() ? termination::cancelled : termination::completed;
    }

private:
    static constexpr int none = -1;
    struct forwarder {
        std::stop_source* to;
        void operator()() const noexcept { to->request_stop(); }
    };
    clock::time_point start_;
    std::optional<clock::time_point> deadline_{};
    std::stop_source halt_{};
    std::atomic<int> why_{none};
    std::stop_callback<forwarder> forward_;  // last: it may fire at once, into halt_
};

}  // namespace certipose
