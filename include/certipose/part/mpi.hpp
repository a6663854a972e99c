// certipose/part/mpi.hpp — a whole-part run across machines with MPI: dynamic load balancing of
// facets over the ranks, threads within each rank, and rank 0 handing every facet to the sink in
// facet order, so the output equals a single-process run's box for box.
//
//   MPI_Init_thread(&argc, &argv, MPI_THREAD_FUNNELED, &provided);   // the program's job
//   certipose::part_solver<> part(mesh, camera, task);               // on every rank
//   auto r = certipose::solve_part_mpi(part, options, sink, MPI_COMM_WORLD);  // sink used on rank 0
//
// The selection is cut into chunks of consecutive work items (facets, or patches of facets:
// part/patches.hpp), so that a chunk solved on a rank is the same items. Rank 0 hands them out on request
// (a rank that finishes early asks again: per-facet cost varies 100x, so a static split would
// leave ranks idle), solves chunks itself on a worker thread, and emits finished chunks in order.
// It hands out at most `window` chunks beyond the oldest one not yet finished, so the results
// it buffers stay bounded. Only the main thread calls MPI (MPI_THREAD_FUNNELED suffices). Each
// rank solves its chunk with part_solver (oneTBB, `options.threads` threads), so budgets and
// skips mean what they mean in one process; the run's box budget, cancellation and progress are
// decided on rank 0, in facet order. Results cross the wire as raw doubles: bounds are copied
// exactly. Needs an MPI implementation (Open MPI: Debian libopenmpi-dev); certipose's other
// headers never include this one.
//
// Errors: an exception on a rank (rank 0's sink failing to write, a throwing progress callback,
// a worker's solve) leaves solve_part_mpi on that rank only, after its own threads are joined;
// the other ranks are still waiting for messages. The caller must end the job: catch it, say
// which rank failed, and call MPI_Abort (certipose-part-mpi does).
#pragma once

#include <mpi.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <condition_variable>
#include <cstdint>
#include <cstring>
#include <deque>
#include <exception>
#include <map>
#include <mutex>
#include <optional>
#include <string>
#include <thread>
#include <vector>

#include "certipose/error.hpp"
#include "certipose/part/part_solver.hpp"

namespace certipose {

namespace detail::part_mpi {

enum tag : int { request = 1, assign = 2, result = 3 };

/// Appends/reads plain values to/from a byte buffer.
struct writer {
    std::string bytes;
    template <class T>
    void put(const T& v) {
        const char* p = reinterpret_cast<const char*>(&v);
        bytes.append(p, p + sizeof(T));
    }
};
struct reader {
    const std::string& bytes;
    std::size_t at = 0;
    template <class T>
    T get() {
        if (at + sizeof(T) > bytes.size()) throw geometry_error("solve_part_mpi: truncated result message");
        T v;
        std::memcpy(&v, bytes.data() + at, sizeof(T));
        at += sizeof(T);
        return v;
    }
};

template <Interval I>
void encode(writer& w, const facet_outcome<I>& o) {
    const facet_record& r = o.record;
    w.put<std::uint64_t>(r.index);
    w.put<std::uint64_t>(r.valid);
    w.put<std::uint64_t>(r.boundary);
    w.put<double>(r.seconds);
    w.put<std::uint8_t>(static_cast<std::uint8_t>(r.termination));
    w.put<std::uint64_t>(r.reason.size());
    w.bytes += r.reason;
    for (std::size_t k = 0; k < boundary_reason_count; ++k) w.put<std::uint64_t>(r.boundary_reasons[k]);
    w.put<std::uint64_t>(r.dropped);
    w.put<std::uint64_t>(r.reused_from ? *r.reused_from + 1 : 0);  // 0: paved on its own
    w.put<std::uint64_t>(r.patch ? *r.patch + 1 : 0);              // 0: not a patch's
    w.put<std::uint64_t>(o.boxes.size());
    for (const auto& b : o.boxes) {
        w.put<std::uint8_t>(static_cast<std::uint8_t>(b.cls));
        w.put<std::uint8_t>(static_cast<std::uint8_t>(b.reason));
        for (std::size_t d = 0; d < 3; ++d) {
            w.put<double>(lower(b.box.position[d]));
            w.put<double>(upper(b.box.position[d]));
        }
        for (std::size_t d = 0; d < 3; ++d) {
            w.put<double>(lower(b.box.orientation[d]));
            w.put<double>(upper(b.box.orientation[d]));
        }
    }
}

template <Interval I>
facet_outcome<I> decode(reader& rd) {
    facet_outcome<I> o;
    facet_record& r = o.record;
    r.index = rd.get<std::uint64_t>();
    r.valid = rd.get<std::uint64_t>();
    r.boundary = rd.get<std::uint64_t>();
    r.seconds = rd.get<double>();
    r.termination = static_cast<facet_termination>(rd.get<std::uint8_t>());
    const auto n = rd.get<std::uint64_t>();
    if (rd.at + n > rd.bytes.size()) throw geometry_error("solve_part_mpi: truncated result message");
    r.reason.assign(rd.bytes.data() + rd.at, n);
    rd.at += n;
    for (std::size_t k = 0; k < boundary_reason_count; ++k) r.boundary_reasons[k] = rd.get<std::uint64_t>();
    r.dropped = rd.get<std::uint64_t>();
    if (const auto from = rd.get<std::uint64_t>()) r.reused_from = from - 1;
    if (const auto seed = rd.get<std::uint64_t>()) r.patch = seed - 1;
    const auto boxes = rd.get<std::uint64_t>();
    o.boxes.reserve(boxes);
    const rounding_guard<I> rounding;  // building intervals from exact bounds
    for (std::uint64_t i = 0; i < boxes; ++i) {
        classified_box<I> b;
        b.cls = static_cast<box_class>(rd.get<std::uint8_t>());
        b.reason = static_cast<boundary_reason>(rd.get<std::uint8_t>());
        for (std::size_t d = 0; d < 3; ++d) {
            const double lo = rd.get<double>(), hi = rd.get<double>();
            b.box.position[d] = I(lo, hi);
        }
        for (std::size_t d = 0; d < 3; ++d) {
            const double lo = rd.get<double>(), hi = rd.get<double>();
            b.box.orientation[d] = I(lo, hi);
        }
        o.boxes.push_back(std::move(b));
    }
    return o;
}

}  // namespace detail::part_mpi

/// What solve_part_mpi adds to part_options.
struct mpi_part_options {
    /// Facets per chunk; 0: about 64 chunks per rank, at most 16 facets each.
    std::size_t chunk = 0;
    /// Chunks handed out beyond the oldest unfinished one, per rank (bounds rank 0's buffer).
    std::size_t window = 4;
};

/// Solves the selection of `options` across the ranks of `comm` (see the header comment). Every
/// rank calls it with the same part, options and selection; `sink` is used on rank 0 only. On
/// rank 0 the result describes the whole run; elsewhere, the facets that rank solved.
template <class Policies, class Sink>
    requires PartSink<Sink, typename part_solver<Policies>::interval_type>
part_result solve_part_mpi(const part_solver<Policies>& part, const part_options& options, Sink& sink,
                           MPI_Comm comm = MPI_COMM_WORLD, mpi_part_options mpi = {}) {
    using I = typename part_solver<Policies>::interval_type;
    namespace pm = detail::part_mpi;
    using clock = std::chrono::steady_clock;
    int rank = 0, ranks = 1;
    MPI_Comm_rank(comm, &rank);
    MPI_Comm_size(comm, &ranks);

    // The selection, the run's budgets, stop and progress, and the order of results: the same
    // scheduler as a oneTBB run's (part/scheduler.hpp), used on rank 0; the others only read
    // the selection to cut chunks.
    const auto regions = part.patches(options);
    part_schedule schedule(options, part.solver().part().num_faces(), [&](std::size_t f) { return part.work_estimate(f); },
                           regions.get());
    const work_plan& plan = schedule.plan();
    run_context& run = schedule.context();
    // Chunks of whole work items: a chunk's facets, grouped again by the rank, are the same items.
    const std::size_t items = plan.items();
    const std::size_t per_chunk = mpi.chunk ? mpi.chunk
                                            : std::clamp<std::size_t>(items / (64 * static_cast<std::size_t>(ranks)), 1, 16);
    const std::size_t chunks = (items + per_chunk - 1) / per_chunk;
    const auto chunk_options = [&](std::size_t c) {
        part_options o = options;
        const std::size_t last = std::min(items, (c + 1) * per_chunk) - 1;
        o.facets.assign(plan.order.begin() + static_cast<std::ptrdiff_t>(plan.begin_of(c * per_chunk)),
                        plan.order.begin() + static_cast<std::ptrdiff_t>(plan.ends[last]));
        o.max_boxes.reset();  // the run's budget is decided on rank 0, in order
        o.time_limit.reset();
        o.progress = {};
        return o;
    };
    const auto solve_chunk = [&](std::size_t c, std::stop_token stop) {
        part_options o = chunk_options(c);
        o.stop = stop;
        collecting_sink<I> local;
        const part_result r = part.solve(o, local);
        std::string bytes;
        pm::writer w;
        w.put<std::uint64_t>(c);
        w.put<std::uint8_t>(r.facets.size() == o.facets.size() ? 1 : 0);  // complete?
        w.put<std::uint64_t>(local.outcomes.size());
        for (const auto& out : local.outcomes) pm::encode(w, out);
        return std::move(w.bytes);
    };

    if (rank != 0) {  // ---- a worker: ask, solve, send, until told to stop ---------------------
        part_result out;
        const auto start = clock::now();
        for (;;) {
            const int dummy = 0;
            MPI_Send(&dummy, 1, MPI_INT, 0, pm::request, comm);
            std::int64_t c = -1;
            MPI_Recv(&c, 1, MPI_INT64_T, 0, pm::assign, comm, MPI_STATUS_IGNORE);
            if (c < 0) break;
            const std::string bytes = solve_chunk(static_cast<std::size_t>(c), {});
            MPI_Send(bytes.data(), static_cast<int>(bytes.size()), MPI_BYTE, 0, pm::result, comm);
            out.facets_selected += chunk_options(static_cast<std::size_t>(c)).facets.size();
        }
        out.seconds = std::chrono::duration<double>(clock::now() - start).count();
        return out;
    }

    // ---- rank 0: hand out chunks, solve some itself, emit in order --------------------------------
    std::size_t next_chunk = 0, next_emit = 0;
    std::map<std::size_t, std::string> finished;  // chunk → its encoded result
    std::vector<int> waiting;                     // workers whose request is not answered yet
    int workers_left = ranks - 1;

    std::mutex m;
    std::condition_variable cv;
    std::deque<std::size_t> local_queue;
    std::vector<std::pair<std::size_t, std::string>> local_done;
    bool local_stop = false;
    std::exception_ptr local_error;  // what the local worker threw, rethrown on the main thread
    std::stop_source local_cancel;
    std::thread local_worker([&] {
        try {
            for (;;) {
                std::size_t c = 0;
                {
                    std::unique_lock lock(m);
                    cv.wait(lock, [&] { return local_stop || !local_queue.empty(); });
                    if (local_queue.empty()) return;
                    c = local_queue.front();
                    local_queue.pop_front();
                }
                std::string bytes = solve_chunk(c, local_cancel.get_token());
                {
                    std::lock_guard lock(m);
                    local_done.emplace_back(c, std::move(bytes));
                }
            }
        } catch (...) {
            const std::lock_guard lock(m);
            local_error = std::current_exception();
        }
    });
    // Stops and joins the local worker however this function is left: an exception from the sink
    // or the progress callback must not unwind past a joinable std::thread (std::terminate).
    const auto stop_local = [&] {
        {
            std::lock_guard lock(m);
            local_stop = true;
            local_queue.clear();
        }
        local_cancel.request_stop();
        cv.notify_one();
        if (local_worker.joinable()) local_worker.join();
    };
    struct local_joiner {
        const decltype(stop_local)& stop;
        ~local_joiner() { stop(); }
    } joiner{stop_local};
    const std::size_t window = std::max<std::size_t>(1, mpi.window) * static_cast<std::size_t>(ranks);
    const auto may_hand_out = [&] { return !run.stop_requested() && next_chunk < chunks && next_chunk < next_emit + window; };
    bool local_busy = false;

    const auto emit_ready = [&] {
        while (!run.stop_requested()) {
            const auto it = finished.find(next_emit);
            if (it == finished.end()) return;
            pm::reader rd{it->second};
            rd.get<std::uint64_t>();
            const bool complete = rd.get<std::uint8_t>() != 0;
            const auto n = rd.get<std::uint64_t>();
            // emit hands over nothing once the run stops, but the rest of an item begun
            for (std::uint64_t i = 0; i < n; ++i) schedule.emit(sink, pm::decode<I>(rd));
            if (!complete) run.stop(termination::cancelled);
            finished.erase(it);
            ++next_emit;
        }
    };

    while (next_emit < chunks && !run.stop_requested()) {
        if (run.past_deadline()) run.stop(termination::deadline);
        // Answer waiting workers and feed the local worker while the window allows.
        while (!waiting.empty() && may_hand_out()) {
            const std::int64_t c = static_cast<std::int64_t>(next_chunk++);
            MPI_Send(&c, 1, MPI_INT64_T, waiting.back(), pm::assign, comm);
            waiting.pop_back();
        }
        if (!local_busy && may_hand_out()) {
            std::lock_guard lock(m);
            local_queue.push_back(next_chunk++);
            local_busy = true;
            cv.notify_one();
        }
        // Messages from the workers.
        int flag = 0;
        MPI_Status st;
        MPI_Iprobe(MPI_ANY_SOURCE, MPI_ANY_TAG, comm, &flag, &st);
        if (flag) {
            if (st.MPI_TAG == pm::request) {
                int dummy = 0;
                MPI_Recv(&dummy, 1, MPI_INT, st.MPI_SOURCE, pm::request, comm, MPI_STATUS_IGNORE);
                waiting.push_back(st.MPI_SOURCE);
            } else {
                int size = 0;
                MPI_Get_count(&st, MPI_BYTE, &size);
                std::string bytes(static_cast<std::size_t>(size), '\0');
                MPI_Recv(bytes.data(), size, MPI_BYTE, st.MPI_SOURCE, pm::result, comm, MPI_STATUS_IGNORE);
                pm::reader rd{bytes};
                const auto c = static_cast<std::size_t>(rd.get<std::uint64_t>());
                finished.emplace(c, std::move(bytes));
            }
        }
        {
            std::lock_guard lock(m);
            if (local_error) std::rethrow_exception(local_error);
            for (auto& [c, bytes] : local_done) finished.emplace(c, std::move(bytes)), local_busy = false;
            local_done.clear();
        }
        emit_ready();
        if (!flag) std::this_thread::sleep_for(std::chrono::microseconds(200));
    }

    // Wind down: stop the local worker, tell every worker to stop (draining what they send).
    stop_local();
    if (local_error) std::rethrow_exception(local_error);
    while (workers_left > 0) {
        for (int w : waiting) {
            const std::int64_t stop = -1;
            MPI_Send(&stop, 1, MPI_INT64_T, w, pm::assign, comm);
            --workers_left;
        }
        waiting.clear();
        if (workers_left == 0) break;
        MPI_Status st;
        MPI_Probe(MPI_ANY_SOURCE, MPI_ANY_TAG, comm, &st);
        if (st.MPI_TAG == pm::request) {
            int dummy = 0;
            MPI_Recv(&dummy, 1, MPI_INT, st.MPI_SOURCE, pm::request, comm, MPI_STATUS_IGNORE);
            waiting.push_back(st.MPI_SOURCE);
        } else {  // a chunk finished after the end: not emitted
            int size = 0;
            MPI_Get_count(&st, MPI_BYTE, &size);
            std::string bytes(static_cast<std::size_t>(size), '\0');
            MPI_Recv(bytes.data(), size, MPI_BYTE, st.MPI_SOURCE, pm::result, comm, MPI_STATUS_IGNORE);
        }
    }
    return schedule.finish(part_threads(options));
}

}  // namespace certipose
