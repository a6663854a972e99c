// certipose._core — the compiled half of the Python module `certipose` (docs/python.md).
//
// It binds the precompiled default pipelines (detail/precompiled.hpp: the default pipeline with
// a calibrated camera under the aabb, boolean and no-occlusion policies), so importing it
// compiles nothing. The Python half (python/certipose/__init__.py) turns dicts into the camera
// JSON and codes into strings; everything that decides an answer is here, in the library.
//
// Threads and the GIL: every solve, part run, inspection, plan and verification runs on a thread
// of its own while the calling thread waits with the GIL released, waking every 50 ms to run
// Python's signal handlers. A KeyboardInterrupt (or any exception a handler raises) stops the
// work through its stop token; the call then raises it once the work has returned. Progress
// callbacks are called on the calling thread, never on a worker, so they may do anything Python
// allows. Worker threads never touch a Python object.
//
// Arrays out are views into one buffer owned by a capsule: a facet's (N, 6, 2) bounds are
// `positions` (N, 3, 2) and `orientations` (N, 3, 2) without a copy. Arrays in (a mesh's V, F)
// are copied once into the library's mesh, which validates them and owns its data.
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <certipose/cgal.hpp>
#include <certipose/coverage/inspect_boxes.hpp>
#include <certipose/io/box_store.hpp>
#include <certipose/io/json.hpp>
#include <certipose/io/make_plan.hpp>
#include <certipose/io/moveit_yaml.hpp>
#include <certipose/io/output_files.hpp>
#include <certipose/io/part_files.hpp>
#include <certipose/io/plan_export.hpp>
#include <certipose/io/plan_files.hpp>
#include <certipose/io/plan_gltf.hpp>
#include <certipose/io/plan_html.hpp>
#include <certipose/io/plan_occluders.hpp>
#include <certipose/io/plan_sheet.hpp>
#include <certipose/io/step_path.hpp>
#include <certipose/geometry/sample_part.hpp>

#include "example_camera.hpp"
#if defined(CERTIPOSE_PYTHON_READ_STEP)
#include <certipose/io/read_step.hpp>
#endif
#include <certipose/io/verify_poses.hpp>
#include <certipose/part/part_solver.hpp>
#include <certipose/part/selection.hpp>
#include <certipose/solver/occlusion_choice.hpp>
#include <certipose/solver/solve_settings.hpp>

#include <atomic>
#include <chrono>
#include <cmath>
#include <filesystem>
#include <condition_variable>
#include <cstdint>
#include <deque>
#include <future>
#include <memory>
#include <mutex>
#include <optional>
#include <stop_token>
#include <string>
#include <thread>
#include <tuple>
#include <type_traits>
#include <utility>
#include <variant>
#include <vector>

namespace py = pybind11;
namespace cp = certipose;

// The web viewer's HTML template and bundled script (cmake/certipose_viewer.cmake; empty when the
// build had no Node.js or no `npm ci` in web/): export(format="html") embeds them.
extern const std::string_view certipose_viewer_template;
extern const std::string_view certipose_viewer_script;

namespace {

using I = cp::boost_interval;
/// The part solver of one occlusion policy: the programs' pipeline (cp::calibrated_pipeline).
template <class Occlusion>
using part_for = cp::part_solver<cp::calibrated_pipeline<Occlusion>>;
using any_part = std::variant<std::unique_ptr<part_for<cp::aabb_occlusion>>, std::unique_ptr<part_for<cp::boolean_occlusion>>,
                              std::unique_ptr<part_for<cp::no_occlusion>>>;

constexpr auto poll = std::chrono::milliseconds(50);

// ---- errors -------------------------------------------------------------------------------
// The library's error types become the Python classes of certipose/_errors.py (subclasses of
// ValueError, IndexError and OSError), carrying the field, index or path the C++ error names.
void translate(std::exception_ptr p) {
    const auto raise = [](const char* name, const std::exception& e, py::dict attrs) {
        py::object cls = py::module_::import("certipose._errors").attr(name);
        py::object err = cls(e.what());
        for (auto item : attrs) py::setattr(err, item.first, item.second);
        PyErr_SetObject(cls.ptr(), err.ptr());
    };
    try {
        if (p) std::rethrow_exception(p);
    } catch (const cp::invalid_argument& e) {
        raise("InvalidArgument", e, py::dict(py::arg("field") = e.field()));
    } catch (const cp::out_of_range& e) {
        raise("OutOfRange", e, py::dict(py::arg("field") = e.field(), py::arg("index") = e.index(), py::arg("size") = e.size()));
    } catch (const cp::mesh_error& e) {
        raise("MeshError", e, py::dict());
    } catch (const cp::io_error& e) {
        raise("FileError", e, py::dict(py::arg("filename") = e.path()));
    } catch (const cp::geometry_error& e) {
        raise("GeometryError", e, py::dict());
    } catch (const cp::error& e) {
        raise("Error", e, py::dict());
    }
}

// ---- waiting with the GIL released --------------------------------------------------------

/// Runs `work(stop_token)` on a thread of its own; see the header comment. `tick()` (GIL held)
/// is called at each wake-up, for progress; false stops the work. Returns its result, rethrows
/// its exception, or raises the Python exception a signal handler or `tick` raised.
template <class F, class Tick>
auto run_released(F&& work, Tick&& tick) {
    using R = std::invoke_result_t<F&, std::stop_token>;
    std::stop_source stop;
    std::packaged_task<R()> task([&] { return work(stop.get_token()); });
    std::future<R> done = task.get_future();
    std::thread worker(std::move(task));
    std::exception_ptr raised;
    for (;;) {
        {
            py::gil_scoped_release released;
            if (done.wait_for(poll) == std::future_status::ready) break;
        }
        try {
            if (PyErr_CheckSignals() != 0) throw py::error_already_set();
            if (!tick()) stop.request_stop();
        } catch (...) {
            raised = std::current_exception();
            stop.request_stop();
            py::gil_scoped_release released;
            done.wait();
            break;
        }
    }
    worker.join();
    if (raised) std::rethrow_exception(raised);
    return done.get();
}

template <class F>
auto run_released(F&& work) {
    return run_released(std::forward<F>(work), [] { return true; });
}

// ---- meshes and cameras ------------------------------------------------------------------

/// "(4, 2)": an array's shape, for messages.
std::string shape_text(const py::array& a) {
    std::string out = "(";
    for (py::ssize_t i = 0; i < a.ndim(); ++i) out += (i ? ", " : "") + std::to_string(a.shape(i));
    return out + (a.ndim() == 1 ? ",)" : ")");
}

std::shared_ptr<const cp::triangle_mesh> mesh_from_arrays(py::array_t<double, py::array::c_style | py::array::forcecast> v,
                                                          py::array_t<std::int64_t, py::array::c_style | py::array::forcecast> f) {
    if (v.ndim() != 2 || v.shape(1) != 3)
        throw cp::invalid_argument("vertices", "Mesh: vertices must be an (N, 3) array, got shape " + shape_text(v));
    if (f.ndim() != 2 || f.shape(1) != 3)
        throw cp::invalid_argument("faces", "Mesh: faces must be an (M, 3) array of vertex indices, got shape " + shape_text(f));
    std::vector<Eigen::Vector3d> vertices(static_cast<std::size_t>(v.shape(0)));
    const auto vv = v.unchecked<2>();
    for (py::ssize_t i = 0; i < v.shape(0); ++i) vertices[i] = {vv(i, 0), vv(i, 1), vv(i, 2)};
    std::vector<cp::face_indices> faces(static_cast<std::size_t>(f.shape(0)));
    const auto ff = f.unchecked<2>();
    for (py::ssize_t i = 0; i < f.shape(0); ++i)
        for (int k = 0; k < 3; ++k) {
            const std::int64_t x = ff(i, k);
            if (x < 0 || x > std::int64_t{0xffffffff})
                throw cp::mesh_error("Mesh: face " + std::to_string(i) + " refers to vertex " + std::to_string(x) +
                                     ", out of range (the mesh has " + std::to_string(vertices.size()) + " vertices)");
            faces[i][k] = static_cast<std::uint32_t>(x);
        }
    return std::make_shared<const cp::triangle_mesh>(std::move(vertices), std::move(faces));
}

/// A camera and task as the solver reads them (io/json.hpp's camera_task).
struct camera_spec {
    cp::camera_task input;
};

camera_spec camera_from_json(const std::string& text, const std::string& source, const std::string& base_dir) {
    return {cp::parse_camera_task(text, source, base_dir)};
}

camera_spec camera_from_file(const std::string& path, std::optional<std::pair<double, double>> working_distance,
                             std::optional<double> min_view_angle) {
    auto input = cp::read_camera_input(path);
    if (auto* task = std::get_if<cp::camera_task>(&input)) {
        if (working_distance || min_view_angle)
            throw cp::invalid_argument(working_distance ? "working_distance" : "min_view_angle",
                                       std::string(working_distance ? "working_distance" : "min_view_angle") +
                                           ": only with a calibration file; " + path +
                                           " is a camera/task JSON, which has its own d_min, d_max and task.min_view_angle");
        return {std::move(*task)};
    }
    if (!working_distance || !min_view_angle)
        throw cp::invalid_argument(!working_distance ? "working_distance" : "min_view_angle",
                                   path + " is a calibration file (no working distance or task): give " +
                                       (!working_distance ? "working_distance=(d_min, d_max)" : "min_view_angle"));
    cp::inspection_task task;
    task.min_view_angle = *min_view_angle;
    try {
        return {cp::camera_task_from_calibration(std::get<cp::calibration>(input),
                                                 {working_distance->first, working_distance->second}, task)};
    } catch (const cp::invalid_argument& e) {
        throw cp::invalid_argument(e.field(), path + ": " + e.what());
    }
}

// ---- options ------------------------------------------------------------------------------

/// The per-facet options, as the programs' flags give them (solver/solve_settings.hpp; the
/// Python keywords are its field names).
using facet_settings = cp::solve_settings;

// ---- results as arrays --------------------------------------------------------------------

/// Boxes as one (N, 6, 2) buffer of bounds (rows x, y, z, φ, γ, β), their class codes (0 VALID,
/// 1 BOUNDARY) and reason codes (boundary_reason; -1 for VALID).
struct box_arrays {
    py::array_t<double> bounds;
    py::array_t<std::uint8_t> classes;
    py::array_t<std::int8_t> reasons;
};

template <class T>
py::array_t<T> owned(std::vector<std::size_t> shape, std::vector<T>&& data) {
    auto* held = new std::vector<T>(std::move(data));
    py::capsule owner(held, [](void* p) { delete static_cast<std::vector<T>*>(p); });
    return py::array_t<T>(shape, held->data(), owner);
}

/// Boxes as plain vectors (no Python object: a worker thread may build them).
struct box_vectors {
    std::vector<double> bounds;  ///< 12 per box
    std::vector<std::uint8_t> classes;
    std::vector<std::int8_t> reasons;

    void append(const std::vector<cp::classified_box<I>>& boxes) {
        const std::size_t at = classes.size();
        bounds.resize(12 * (at + boxes.size()));
        classes.resize(at + boxes.size());
        reasons.resize(at + boxes.size());
        for (std::size_t i = 0; i < boxes.size(); ++i) {
            const auto rec = cp::to_record(boxes[i]);
            double* out = &bounds[12 * (at + i)];
            for (std::size_t k = 0; k < 3; ++k) {
                out[2 * k] = rec.position[k][0];
                out[2 * k + 1] = rec.position[k][1];
                out[6 + 2 * k] = rec.orientation[k][0];
                out[6 + 2 * k + 1] = rec.orientation[k][1];
            }
            classes[at + i] = rec.cls == cp::box_class::valid ? 0 : 1;
            reasons[at + i] = rec.reason ? static_cast<std::int8_t>(*rec.reason) : std::int8_t{-1};
        }
    }
    /// The arrays, owning the vectors' memory (no copy).
    box_arrays wrap() && {
        const std::size_t n = classes.size();
        return {owned<double>({n, 6, 2}, std::move(bounds)), owned<std::uint8_t>({n}, std::move(classes)),
                owned<std::int8_t>({n}, std::move(reasons))};
    }
};

box_arrays to_arrays(const std::vector<cp::classified_box<I>>& boxes) {
    box_vectors v;
    v.append(boxes);
    return std::move(v).wrap();
}

py::dict stats_dict(const cp::solve_stats& s) {
    py::dict d;
    cp::for_each_stats_field([&](const auto& field) {
        const auto& v = s.*(field.member);
        using T = std::decay_t<decltype(v)>;
        const std::string name(field.name);
        if constexpr (std::is_same_v<T, cp::termination>) {
            d[name.c_str()] = cp::to_string(v);
        } else if constexpr (std::is_same_v<T, std::array<std::size_t, cp::boundary_reason_count>>) {
            py::dict by;
            for (std::size_t k = 0; k < v.size(); ++k)
                if (v[k]) by[py::str(std::string(cp::to_string(static_cast<cp::boundary_reason>(k))))] = v[k];
            d[name.c_str()] = by;
        } else {
            d[name.c_str()] = v;
        }
    });
    return d;
}

py::dict record_dict(const cp::facet_record& r) {
    py::dict reasons;
    for (std::size_t k = 0; k < r.boundary_reasons.size(); ++k)
        if (r.boundary_reasons[k])
            reasons[py::str(std::string(cp::to_string(static_cast<cp::boundary_reason>(k))))] = r.boundary_reasons[k];
    return py::dict(py::arg("index") = r.index, py::arg("valid") = r.valid, py::arg("boundary") = r.boundary,
                    py::arg("seconds") = r.seconds, py::arg("termination") = cp::to_string(r.termination),
                    py::arg("reason") = r.reason, py::arg("dropped") = r.dropped,
                    py::arg("reused_from") = r.reused_from ? py::object(py::int_(*r.reused_from)) : py::object(py::none()),
                    py::arg("boundary_reasons") = reasons);
}

/// One facet's answer: the arrays, and either the solver's stats (solve_facet) or the part
/// run's record (solve_part).
struct facet_result {
    std::size_t facet = 0;
    box_arrays boxes;
    py::dict stats;   ///< solve_facet
    py::dict record;  ///< solve_part
};

// ---- the solver ---------------------------------------------------------------------------

/// A part, a camera and an occlusion policy: the occlusion scene is built once here and every
/// solve of the part reuses it.
class solver {
public:
    /// `occluders`: extra meshes of the scene, each with the path and scale the documents record;
    /// `keep_in` / `keep_out`: camera regions ("box:..." or "sphere:...", docs/conventions.md).
    solver(std::shared_ptr<const cp::triangle_mesh> mesh, camera_spec camera, const std::string& occlusion,
           const std::string& semantics, const std::vector<std::tuple<std::shared_ptr<cp::triangle_mesh>, std::string, double>>& occluders,
           const std::vector<std::string>& keep_in, const std::vector<std::string>& keep_out)
        : mesh_(std::move(mesh)), input_(std::move(camera.input)), occlusion_(occlusion) {
        if (!mesh_) throw cp::invalid_argument("mesh", "Solver: mesh is None");
        // As the programs do: a placement tolerance without a datum is about the part's centroid,
        // resolved here so that every output records the datum the boxes were certified about.
        if (input_.task.placement && !input_.task.placement->datum)
            input_.task.placement->datum = cp::surface_centroid(*mesh_);
        cp::mesh_semantics sem = cp::mesh_semantics::automatic;
        if (semantics == "solid") sem = cp::mesh_semantics::solid;
        else if (semantics == "soup") sem = cp::mesh_semantics::soup;
        else if (semantics != "auto")
            throw cp::invalid_argument("mesh_semantics", "mesh_semantics must be \"auto\", \"solid\" or \"soup\", got \"" + semantics + "\"");
        std::vector<cp::triangle_mesh>& extra = occluders_;
        for (const auto& [m, path, scale] : occluders) {
            if (!m) throw cp::invalid_argument("occluders", "Solver: an occluder is None");
            extra.push_back(*m);
            scene_.occluders.push_back(cp::describe_occluder(path, scale, *m));
        }
        for (std::size_t i = 0; i < keep_in.size(); ++i)
            scene_.regions.keep_in.push_back(cp::parse_camera_region(keep_in[i], "keep_in[" + std::to_string(i) + "]"));
        for (std::size_t i = 0; i < keep_out.size(); ++i)
            scene_.regions.keep_out.push_back(cp::parse_camera_region(keep_out[i], "keep_out[" + std::to_string(i) + "]"));
        scene_.regions.validate();
        const cp::calibrated_camera cam = input_.calibrated();
        const auto build = [&]<class O>() {
            const cp::inspection_task task = input_.task;
            return run_released([&](std::stop_token) {
                return any_part(std::make_unique<part_for<O>>(
                    *mesh_, cam, task, typename part_for<O>::setup{.occluders = extra, .semantics = sem}));
            });
        };
        part_ = cp::visit_occlusion(cp::parse_occlusion_choice(occlusion),
                                    [&]<class O>(std::type_identity<O>) { return build.template operator()<O>(); });
    }

    /// The occluders and camera regions, as the documents record them.
    const cp::scene_record& scene() const { return scene_; }
    /// The occluder meshes themselves (make_plan names the facets resting on them).
    const std::vector<cp::triangle_mesh>& occluders() const { return occluders_; }
    const cp::triangle_mesh& mesh() const { return *mesh_; }
    std::shared_ptr<const cp::triangle_mesh> mesh_ptr() const { return mesh_; }
    const cp::camera_task& camera() const { return input_; }
    const std::string& occlusion() const { return occlusion_; }

    template <class F>
    decltype(auto) visit(F&& f) const {
        return std::visit([&](const auto& p) -> decltype(auto) { return f(*p); }, part_);
    }

    facet_result solve_facet(std::size_t facet, const facet_settings& s) const {
        (void)mesh_->facet(facet);  // out_of_range: "facet 9999 is out of range (valid: 0..N)"
        cp::solve_options o = cp::to_solve_options(s);
        auto result = run_released([&](std::stop_token stop) {
            o.stop = stop;
            auto r = visit([&](const auto& part) { return part.solver().solve(facet, o); });
            cp::restrict_to_regions(r, scene_.regions, o.position_eps);  // as certipose-solve does
            return r;
        });
        return {facet, to_arrays(result.boxes), stats_dict(result.stats), py::dict()};
    }

    /// What the occlusion's survey found when it reads the scene as a triangle soup (the
    /// programs warn with it); None when it reads clean closed solids or checks nothing.
    py::object survey() const {
        py::object out = py::none();
        visit([&](const auto& part) {
            const auto& occ = part.solver().occlusion();
            if constexpr (requires { occ.survey(); })
                if (const cp::mesh_survey* v = occ.survey())
                    out = py::dict(py::arg("why_not_solid") = std::string(occ.why_not_solid()), py::arg("bodies") = v->bodies,
                                   py::arg("closed_bodies") = v->closed_bodies, py::arg("inward_bodies") = v->inward_bodies,
                                   py::arg("open_edges") = v->open_edges, py::arg("nonmanifold_edges") = v->nonmanifold_edges,
                                   py::arg("duplicate_faces") = v->duplicate_faces,
                                   py::arg("intersecting_pairs") = v->intersecting_pairs, py::arg("buried") = v->buried,
                                   py::arg("covered") = v->covered, py::arg("examples") = v->examples);
        });
        return out;
    }

private:
    std::shared_ptr<const cp::triangle_mesh> mesh_;
    cp::camera_task input_;
    std::string occlusion_;
    cp::scene_record scene_;
    std::vector<cp::triangle_mesh> occluders_;
    any_part part_;
};

// ---- a whole-part run, as an iterator -----------------------------------------------------

/// A certipose-part run on a thread of its own. Iterated, it hands each finished facet to
/// Python in facet order (a bounded queue: a slow consumer holds the run back rather than filling
/// memory); collected (`collect`), the sink appends every box to one set of arrays, and Python
/// only hears of progress. The facets' boxes become arrays on the sink's thread either way.
class part_run {
public:
    part_run(std::shared_ptr<const solver> s, cp::part_options opt, py::object progress, bool collect)
        : solver_(std::move(s)), progress_(std::move(progress)), collect_(collect) {
        opt.stop = stop_.get_token();
        progress_is_none_ = progress_.is_none();
        // Only with a callback: the part solver then also estimates every facet's work (the ETA).
        if (!progress_is_none_)
            opt.progress = [this](const cp::part_progress& p) {
                std::lock_guard lock(mutex_);
                latest_ = p;
                fresh_ = true;
                changed_.notify_all();
                return !stop_.stop_requested();
            };
        worker_ = std::thread([this, opt = std::move(opt)] {
            try {
                sink sk{this};
                cp::part_result r = solver_->visit([&](const auto& part) { return part.solve(opt, sk); });
                std::lock_guard lock(mutex_);
                result_ = std::move(r);
            } catch (...) {
                std::lock_guard lock(mutex_);
                failure_ = std::current_exception();
            }
            std::lock_guard lock(mutex_);
            finished_ = true;
            changed_.notify_all();
        });
    }
    part_run(const part_run&) = delete;
    part_run& operator=(const part_run&) = delete;
    ~part_run() { stop_and_join(); }

    /// The next finished facet, or nothing once the run has ended (then `summary` is set).
    std::optional<facet_result> next() {
        for (;;) {
            std::optional<queued> got;
            bool ended = false;
            {
                py::gil_scoped_release released;
                std::unique_lock lock(mutex_);
                changed_.wait_for(lock, poll, [&] { return !queue_.empty() || finished_ || (fresh_ && !progress_is_none_); });
                if (!queue_.empty()) {
                    got = std::move(queue_.front());
                    queue_.pop_front();
                    changed_.notify_all();
                } else if (finished_) {
                    ended = true;
                }
            }
            report_progress();
            if (got) return facet_result{got->record.index, std::move(got->boxes).wrap(), py::dict(), record_dict(got->record)};
            if (ended) {
                join();
                if (failure_) std::rethrow_exception(std::exchange(failure_, nullptr));
                return std::nullopt;
            }
        }
    }

    /// Collected: waits for the end of the run; the boxes of every facet, in facet order, as
    /// (facets (N,), bounds (N, 6, 2), class codes, reason codes).
    py::tuple collect() {
        for (;;) {
            bool ended = false;
            {
                py::gil_scoped_release released;
                std::unique_lock lock(mutex_);
                changed_.wait_for(lock, poll, [&] { return finished_ || (fresh_ && !progress_is_none_); });
                ended = finished_;
            }
            report_progress();
            if (ended) break;
        }
        join();
        if (failure_) std::rethrow_exception(std::exchange(failure_, nullptr));
        const std::size_t n = all_facets_.size();
        box_arrays arrays = std::move(all_).wrap();
        return py::make_tuple(owned<std::int64_t>({n}, std::move(all_facets_)), arrays.bounds, arrays.classes, arrays.reasons);
    }

    void cancel() {
        stop_.request_stop();
        changed_.notify_all();  // a sink waiting for room in the queue wakes and sees the stop
    }

    py::dict summary() const {
        std::lock_guard lock(mutex_);
        if (!result_) throw cp::error("PartRun: the run has not ended (iterate it to the end first)");
        const cp::part_result& r = *result_;
        py::list records;
        for (const auto& f : r.facets) records.append(record_dict(f));
        return py::dict(py::arg("facets") = records, py::arg("facets_selected") = r.facets_selected, py::arg("valid") = r.valid,
                        py::arg("boundary") = r.boundary, py::arg("skipped") = r.skipped, py::arg("seconds") = r.seconds,
                        py::arg("threads") = r.threads, py::arg("reused") = r.reused,
                        py::arg("termination") = cp::to_string(r.reason));
    }

private:
    struct queued {
        cp::facet_record record;
        box_vectors boxes;
    };
    struct sink {
        part_run* run;
        void facet(const cp::facet_outcome<I>& o) {
            if (run->collect_) {  // straight into the arrays of the whole run (one copy of each box)
                std::lock_guard lock(run->mutex_);
                run->all_.append(o.boxes);
                run->all_facets_.resize(run->all_facets_.size() + o.boxes.size(), static_cast<std::int64_t>(o.record.index));
                return;
            }
            queued q{o.record, {}};
            q.boxes.append(o.boxes);
            std::unique_lock lock(run->mutex_);
            run->changed_.wait(lock, [&] { return run->queue_.size() < capacity || run->stop_.stop_requested(); });
            if (run->abandoned_) return;
            run->queue_.push_back(std::move(q));
            run->changed_.notify_all();
        }
    };
    static constexpr std::size_t capacity = 64;

    /// Calls the progress callback with the latest progress, if any is new (GIL held); a false
    /// return cancels the run, an exception stops it and propagates; a signal handler's
    /// exception (KeyboardInterrupt) likewise.
    void report_progress() {
        std::optional<cp::part_progress> report;
        {
            std::lock_guard lock(mutex_);
            if (fresh_) report = latest_, fresh_ = false;
        }
        try {
            if (report && !progress_is_none_) {
                const py::object keep_going = progress_(py::dict(
                    py::arg("facets_done") = report->facets_done, py::arg("facets_total") = report->facets_total,
                    py::arg("valid") = report->valid, py::arg("boundary") = report->boundary, py::arg("seconds") = report->seconds,
                    py::arg("seconds_left") = report->seconds_left));
                if (!keep_going.is_none() && !keep_going.cast<bool>()) cancel();
            }
            if (PyErr_CheckSignals() != 0) throw py::error_already_set();
        } catch (...) {
            stop_and_join();
            throw;
        }
    }

    void join() {
        if (worker_.joinable()) {
            py::gil_scoped_release released;
            worker_.join();
        }
    }
    /// Stops the run and waits for its thread (the queue is dropped: nobody will read it).
    void stop_and_join() {
        {
            std::lock_guard lock(mutex_);
            abandoned_ = true;
            queue_.clear();
        }
        stop_.request_stop();
        changed_.notify_all();
        if (worker_.joinable()) {
            if (PyGILState_Check()) {
                py::gil_scoped_release released;
                worker_.join();
            } else {
                worker_.join();
            }
        }
    }

    std::shared_ptr<const solver> solver_;
    py::object progress_;
    bool progress_is_none_ = true;
    const bool collect_;
    std::stop_source stop_;
    mutable std::mutex mutex_;
    std::condition_variable changed_;
    std::deque<queued> queue_;
    box_vectors all_;                       ///< collected: the boxes of every facet so far
    std::vector<std::int64_t> all_facets_;  ///< collected: their facets
    cp::part_progress latest_{};
    bool fresh_ = false, finished_ = false, abandoned_ = false;
    std::optional<cp::part_result> result_;
    std::exception_ptr failure_;
    std::thread worker_;
};

std::unique_ptr<part_run> start_part(std::shared_ptr<solver> s, const facet_settings& fs, std::optional<std::string> facets,
                                     std::size_t threads, bool boundary, std::optional<std::size_t> keep_largest,
                                     std::optional<std::size_t> max_boxes_total, std::optional<double> time_limit_total,
                                     bool reuse, py::object progress, bool collect) {
    cp::part_options opt;
    opt.facet = cp::to_solve_options(fs);
    if (facets) opt.facets = cp::parse_facet_selection(*facets, s->mesh().num_faces());
    opt.threads = threads;
    opt.keep_boundary = boundary;
    opt.keep_largest = keep_largest;
    opt.max_boxes = max_boxes_total;
    opt.reuse.translates = reuse;
    if (time_limit_total) opt.time_limit = cp::seconds_setting(*time_limit_total, "time_limit");
    opt.regions = s->scene().regions;  // each facet's VALID boxes, before the sink sees them (as certipose-part)
    return std::make_unique<part_run>(std::move(s), std::move(opt), std::move(progress), collect);
}

// ---- coverage -----------------------------------------------------------------------------

/// C(B) and P(B) of each box (rows of a (N, 6, 2) bounds array, as solve_facet returns them).
py::list inspect(const solver& s, py::array_t<double, py::array::c_style | py::array::forcecast> bounds, std::size_t threads,
                 bool possible) {
    if (bounds.ndim() != 3 || bounds.shape(1) != 6 || bounds.shape(2) != 2)
        throw cp::invalid_argument("boxes", "inspect: boxes must be an (N, 6, 2) array of bounds (x, y, z, phi, gamma, beta), got shape " +
                                                shape_text(bounds));
    std::vector<cp::pose_box<I>> boxes(static_cast<std::size_t>(bounds.shape(0)));
    const auto b = bounds.unchecked<3>();
    for (py::ssize_t i = 0; i < bounds.shape(0); ++i)
        for (int k = 0; k < 6; ++k) {
            const double lo = b(i, k, 0), hi = b(i, k, 1);
            if (!(lo <= hi) || !std::isfinite(lo) || !std::isfinite(hi))
                throw cp::invalid_argument("boxes", "inspect: box " + std::to_string(i) + " has bounds [" + cp::detail::format_double(lo) +
                                                        ", " + cp::detail::format_double(hi) + "] in row " + std::to_string(k) +
                                                        " (expected finite lower <= upper)");
            (k < 3 ? boxes[i].position.x[k] : boxes[i].orientation.x[k - 3]) = I(lo, hi);
        }
    cp::inspection_run run = run_released([&](std::stop_token stop) {
        cp::inspection_options o;
        o.threads = threads;
        o.stop = stop;
        o.possible_sets = possible;
        return s.visit([&](const auto& part) { return cp::inspect_boxes(part.solver(), boxes, o); });
    });
    py::list out;
    for (auto& c : run.coverage) {
        std::vector<std::int64_t> cert(c.certified.begin(), c.certified.end()), poss(c.possible.begin(), c.possible.end());
        const std::size_t nc = cert.size(), np = poss.size();
        out.append(py::dict(py::arg("certified") = owned<std::int64_t>({nc}, std::move(cert)),
                            py::arg("possible") = owned<std::int64_t>({np}, std::move(poss)),
                            py::arg("certified_area") = c.certified_area, py::arg("possible_area") = c.possible_area));
    }
    return out;
}

// ---- plans, verification, exports ---------------------------------------------------------

/// What every document of a run records of its part and camera: the mesh (path as the caller
/// names it), the camera and task records, as certipose-part's summary.json and certipose-plan's
/// PLAN.json hold them.
cp::part_summary here_record(const solver& s, const std::string& mesh_path, double scale) {
    cp::part_summary here;
    here.mesh = {mesh_path, s.mesh().num_faces(), scale, cp::mesh_digest(s.mesh())};
    s.visit([&](const auto& part) { cp::describe_camera(here, part.solver().camera(), s.camera().task); });
    here.camera.mount_offset = s.camera().mount_offset;
    here.settings.occlusion_checked = s.occlusion() != "none";
    here.scene = s.scene();
    return here;
}

/// The records summary.json would hold of this solver: what a plan compares a run with.
std::string run_record_json(const solver& s) {
    const cp::part_summary here = here_record(s, "", 1.0);
    nlohmann::ordered_json j;
    j["digest"] = here.mesh.digest;
    j["camera"] = cp::detail::json_io::camera_record_json(here.camera);
    j["task"] = cp::detail::json_io::task_record_json(here.task);
    j["occlusion_checked"] = here.settings.occlusion_checked;
    cp::detail::json_io::put_scene(j, here.scene);  // "occluders", "keep_in", "keep_out"
    return j.dump();
}

/// A plan or a verification certifies facets: with occlusion "none" nothing would be proven
/// unoccluded (the programs always check occlusion).
void refuse_unchecked_occlusion(const solver& s, const char* what) {
    if (s.occlusion() == "none")
        throw cp::invalid_argument("occlusion", std::string(what) + ": this solver has occlusion \"none\", which certifies no "
                                                                    "facet; use a solver with occlusion \"aabb\" or \"boolean\"");
}

struct plan_holder {
    cp::plan_document doc;
    double seconds_inspection = 0, seconds_choice = 0;
    bool exact = false;
};

cp::plan_options plan_options_of(std::optional<std::size_t> cameras, std::optional<double> coverage,
                                 std::optional<std::array<double, 2>> tolerance, double lp_seconds,
                                 std::optional<double> exact_seconds, std::size_t threads, bool all_candidates) {
    cp::plan_options o;
    o.cameras = cameras;
    o.coverage = coverage;
    o.tolerance = tolerance;
    o.lp_seconds = lp_seconds;
    o.exact_seconds = exact_seconds;
    o.threads = threads;
    if (all_candidates) o.thinning.reset();
    o.validate();
    return o;
}

cp::facet_record record_from_dict(const py::handle& d) {
    cp::facet_record r;
    r.index = d["index"].cast<std::size_t>();
    r.valid = d["valid"].cast<std::size_t>();
    r.boundary = d["boundary"].cast<std::size_t>();
    const std::string t = d["termination"].cast<std::string>();
    const auto term = cp::facet_termination_from_string(t);
    if (!term) throw cp::invalid_argument("records", "plan: a facet record has termination \"" + t + "\"");
    r.termination = *term;
    return r;
}

/// A plan from a run's VALID boxes: arrays (a run made here, `trusted` when it is known to be of
/// this very solver), or a certipose-part folder (checked against this solver, as certipose-plan
/// checks it).
plan_holder make_plan_py(const solver& s, py::object source, std::size_t per_facet, bool trusted, const std::string& mesh_path,
                         double scale, const cp::plan_options& base, py::object progress) {
    if (per_facet < 1) throw cp::invalid_argument("candidates_per_facet", "candidates_per_facet must be at least 1, got 0");
    refuse_unchecked_occlusion(s, "plan");
    plan_holder out;
    const cp::part_summary here = here_record(s, mesh_path, scale);
    out.doc.mesh = here.mesh;
    out.doc.camera = here.camera;
    out.doc.task = here.task;
    out.doc.scene = here.scene;
    const cp::camera_regions& regions = s.scene().regions;
    cp::candidate_pool<I> pool(per_facet);
    std::vector<cp::facet_record> records;
    std::optional<std::string> folder;
    if (py::isinstance<py::str>(source)) folder = source.cast<std::string>();
    if (folder) {
        const std::filesystem::path dir(*folder);
        run_released([&](std::stop_token) {
            const cp::part_summary run = cp::read_part_summary(dir);
            cp::check_part_run(run, here, (dir / "summary.json").string());
            trusted = !run.mesh.digest.empty();
            records = run.facets;
            cp::add_run_candidates(pool, dir, run, s.mesh().num_faces(), regions);
            return 0;
        });
    } else {
        const py::tuple t = source.cast<py::tuple>();
        const auto facets = t[0].cast<py::array_t<std::int64_t, py::array::c_style | py::array::forcecast>>();
        const auto bounds = t[1].cast<py::array_t<double, py::array::c_style | py::array::forcecast>>();
        const auto classes = t[2].cast<py::array_t<std::uint8_t, py::array::c_style | py::array::forcecast>>();
        for (auto r : t[3].cast<py::list>()) records.push_back(record_from_dict(r));
        const py::ssize_t n = facets.shape(0);
        if (bounds.ndim() != 3 || bounds.shape(0) != n || bounds.shape(1) != 6 || bounds.shape(2) != 2 || classes.shape(0) != n)
            throw cp::invalid_argument("part", "plan: the run's facets " + shape_text(facets) + ", bounds " + shape_text(bounds) +
                                                   " and classes " + shape_text(classes) + " do not match (N,), (N, 6, 2), (N,)");
        const auto f = facets.unchecked<1>();
        const auto b = bounds.unchecked<3>();
        const auto c = classes.unchecked<1>();
        for (py::ssize_t i = 0; i < n; ++i) {
            if (f(i) < 0 || static_cast<std::size_t>(f(i)) >= s.mesh().num_faces())
                throw cp::out_of_range("facet", static_cast<std::size_t>(f(i)), s.mesh().num_faces());
            if (c(i) != 0) continue;
            cp::pose_box<I> box;
            for (int k = 0; k < 3; ++k) {
                box.position.x[k] = I(b(i, k, 0), b(i, k, 1));
                box.orientation.x[k] = I(b(i, k + 3, 0), b(i, k + 3, 1));
            }
            pool.add(static_cast<std::size_t>(f(i)), box);
        }
    }
    const std::vector<cp::candidate_box<I>> candidates = pool.boxes();
    std::atomic<std::size_t> done{0}, all{0};
    cp::plan_options opt = base;
    opt.occluders = s.occluders();
    opt.inspection_progress = [&](std::size_t d, std::size_t a) {
        done = d, all = a;
        return true;
    };
    std::size_t reported = static_cast<std::size_t>(-1);
    const auto tick = [&] {
        if (progress.is_none() || all == 0 || done == reported) return true;
        reported = done;
        const py::object r = progress(done.load(), all.load());
        return r.is_none() || r.cast<bool>();
    };
    const cp::plan_report made = run_released(
        [&](std::stop_token stop) {
            opt.stop = stop;
            return s.visit([&](const auto& part) { return cp::make_plan(out.doc, part.solver(), candidates, records, trusted, opt); });
        },
        tick);
    if (!made.completed) throw cp::error("plan: cancelled by its progress callback");  // (Ctrl-C raised before this)
    out.seconds_inspection = made.seconds_inspection;
    out.seconds_choice = made.seconds_choice;
    out.exact = made.exact;
    return out;
}

/// A plan's export (certipose-export's formats; docs/conventions.md#exports) as bytes.
py::bytes export_plan(const cp::plan_document& plan, const std::string& format, std::shared_ptr<cp::triangle_mesh> mesh,
                      const std::string& parent_frame, const std::string& link, const std::string& title,
                      const std::string& link_prefix, const std::string& robot_name, bool snippet) {
    if (format == "csv") return cp::plan_csv(plan);
    if (format == "urdf")
        return cp::plan_urdf(plan, {.parent_frame = parent_frame, .link_prefix = link_prefix, .robot_name = robot_name,
                                    .snippet = snippet});
    if (format == "moveit") {
        if (link != "optical" && link != "mount")
            throw cp::invalid_argument("link", "link must be \"optical\" or \"mount\", got \"" + link + "\"");
        return cp::plan_moveit_yaml(plan, {.frame_id = parent_frame,
                                           .link = link == "mount" ? cp::constrained_link::mount : cp::constrained_link::optical_frame,
                                           .link_prefix = link_prefix});
    }
    if (format == "ply" || format == "glb" || format == "html" || format == "sheet") {
        if (!mesh) throw cp::invalid_argument("mesh", "export: format \"" + format + "\" draws the part: give the plan's mesh");
        if (mesh->num_faces() != plan.mesh.faces)
            throw cp::invalid_argument("mesh.faces", "export: the plan's mesh.faces (" + std::to_string(plan.mesh.faces) +
                                                         ") is not this mesh's (" + std::to_string(mesh->num_faces()) + ")");
        if (!plan.mesh.digest.empty() && plan.mesh.digest != cp::mesh_digest(*mesh))
            throw cp::invalid_argument("mesh.digest", "export: the plan's mesh.digest (" + plan.mesh.digest + ") is not this mesh's (" +
                                                          cp::mesh_digest(*mesh) + ")");
        if (format == "ply") return cp::plan_ply_text(*mesh, plan);
        // As certipose-export: the plan's occluders are drawn when they can be read as recorded.
        const cp::plan_occluders occluders = cp::read_plan_occluders(plan);
        for (const auto& why : occluders.left_out)
            if (PyErr_WarnEx(PyExc_UserWarning, why.c_str(), 1) != 0) throw py::error_already_set();
        if (format == "sheet") return py::bytes(cp::plan_sheet(*mesh, plan, {.title = title, .occluders = occluders.meshes}));
        const std::string glb = cp::plan_glb(*mesh, plan, occluders.meshes);
        if (format == "glb") return py::bytes(glb);
        if (certipose_viewer_script.empty())
            throw cp::invalid_argument("format", "export: format \"html\": this build has no web viewer (it needs Node.js and "
                                                 "`npm ci` in web/ when configuring; scripts/install-deps.sh does both)");
        return cp::plan_html(plan, glb, mesh->num_faces(), {certipose_viewer_template, certipose_viewer_script}, title);
    }
    throw cp::invalid_argument("format", "export: format must be \"csv\", \"moveit\", \"urdf\", \"ply\", \"glb\", \"html\" or \"sheet\", got \"" +
                                             format + "\"");
}

/// Writes `content` to `path` atomically (a complete file or none; io/output_files.hpp).
void write_atomically(const std::string& path, const std::string& content) {
    cp::output_files files;
    files.add(path, content);
    files.commit();
}

/// certipose-verify's report of each pose: exact poses (N, 6), pose boxes (N, 6, 2), or a
/// POSES.json / PLAN.json file.
py::dict verify_py(const solver& s, py::object poses_in, bool tolerance, py::object progress) {
    refuse_unchecked_occlusion(s, "verify");
    std::vector<cp::pose_input> poses;
    if (py::isinstance<py::str>(poses_in)) {
        poses = cp::read_poses(poses_in.cast<std::string>());
    } else {
        const auto a = poses_in.cast<py::array_t<double, py::array::c_style | py::array::forcecast>>();
        const auto finite = [](double v, py::ssize_t i) {
            if (!std::isfinite(v))
                throw cp::invalid_argument("poses", "verify: pose " + std::to_string(i) + " has a non-finite value " +
                                                        cp::detail::format_double(v));
        };
        if (a.ndim() == 2 && a.shape(1) == 6) {
            const auto v = a.unchecked<2>();
            for (py::ssize_t i = 0; i < a.shape(0); ++i) {
                cp::pose_input p;
                p.form = cp::pose_form::exact;
                std::array<double, 6> x{};
                for (int k = 0; k < 6; ++k) finite(x[k] = v(i, k), i);
                p.pose = x;
                for (int k = 0; k < 3; ++k) {
                    p.position[k] = {x[k], x[k]};
                    p.orientation[k] = {x[k + 3], x[k + 3]};
                }
                poses.push_back(p);
            }
        } else if (a.ndim() == 3 && a.shape(1) == 6 && a.shape(2) == 2) {
            const auto v = a.unchecked<3>();
            for (py::ssize_t i = 0; i < a.shape(0); ++i) {
                cp::pose_input p;
                p.form = cp::pose_form::box;
                for (int k = 0; k < 6; ++k) {
                    const double lo = v(i, k, 0), hi = v(i, k, 1);
                    finite(lo, i), finite(hi, i);
                    if (!(lo <= hi))
                        throw cp::invalid_argument("poses", "verify: pose box " + std::to_string(i) + " has lower > upper in row " +
                                                                std::to_string(k) + " ([" + cp::detail::format_double(lo) + ", " +
                                                                cp::detail::format_double(hi) + "])");
                    (k < 3 ? p.position[k] : p.orientation[k - 3]) = {lo, hi};
                }
                poses.push_back(p);
            }
        } else {
            throw cp::invalid_argument("poses", "verify: poses must be (N, 6) exact poses, (N, 6, 2) pose boxes or a POSES.json path, got shape " +
                                                    shape_text(a));
        }
    }
    std::vector<cp::pose_verification> found(poses.size());
    std::atomic<std::size_t> done{0};
    std::size_t reported = static_cast<std::size_t>(-1);
    double total = 0;
    std::vector<double> areas;
    run_released(
        [&](std::stop_token stop) {
            s.visit([&](const auto& part) {
                using P = typename std::decay_t<decltype(part.solver())>::policies;
                cp::facet_inspector<P> inspector(part.solver());
                areas = inspector.areas();
                for (std::size_t i = 0; i < poses.size() && !stop.stop_requested(); ++i) {
                    found[i] = cp::verify_pose(inspector, poses[i], s.scene().regions, tolerance);
                    done = i + 1;
                }
            });
            return 0;
        },
        [&] {
            if (progress.is_none() || done == reported) return true;
            reported = done;
            const py::object r = progress(done.load(), poses.size());
            return r.is_none() || r.cast<bool>();
        });
    if (done != poses.size()) throw cp::error("verify: cancelled by its progress callback");
    for (double a : areas) total += a;
    py::list list;
    std::vector<char> any(s.mesh().num_faces(), 0);
    double union_area = 0;
    for (std::size_t i = 0; i < poses.size(); ++i) {
        const auto& v = found[i];
        const auto& c = v.coverage;
        for (std::size_t f : c.certified)
            if (!any[f]) any[f] = 1, union_area += areas[f];
        std::vector<std::int64_t> cert(c.certified.begin(), c.certified.end()), poss(c.possible.begin(), c.possible.end());
        const std::size_t nc = cert.size(), np = poss.size();
        py::dict r(py::arg("index") = i, py::arg("kind") = cp::to_string(poses[i].form),
                   py::arg("position") = poses[i].position, py::arg("orientation") = poses[i].orientation,
                   py::arg("facets") = owned<std::int64_t>({nc}, std::move(cert)),
                   py::arg("possible") = owned<std::int64_t>({np}, std::move(poss)),
                   py::arg("certified_area") = c.certified_area, py::arg("possible_area") = c.possible_area,
                   py::arg("coverage") = std::pair<double, double>(total > 0 ? c.certified_area / total : 0.0,
                                                                   total > 0 ? c.possible_area / total : 0.0),
                   py::arg("camera_region") = cp::to_string(v.where));
        if (v.tolerance_position)
            r["tolerance"] = py::dict(py::arg("position") = *v.tolerance_position, py::arg("orientation") = *v.tolerance_orientation,
                                      py::arg("half_widths") = v.half_widths);
        else if (v.tolerance_asked)
            r["tolerance"] = py::none();
        list.append(r);
    }
    return py::dict(py::arg("poses") = list,
                    py::arg("union") = py::dict(py::arg("certified_area") = union_area, py::arg("total_area") = total,
                                                py::arg("coverage") = total > 0 ? union_area / total : 0.0));
}

/// A STEP file read in metres and tessellated (read_step): its Mesh and its CAD model as a dict
/// (unit, deflections, dropped triangles, "face_of" per facet, and per face its id, name,
/// surface, area, deviation and facets); io_error naming the file when this build has no
/// STEP reader.
py::tuple read_step(const std::string& path, std::optional<double> deflection, std::optional<double> angular_deflection) {
#if defined(CERTIPOSE_PYTHON_READ_STEP)
    cp::step_options o;
    o.deflection = deflection;
    if (angular_deflection) o.angular_deflection = *angular_deflection;
    cp::step_part p = run_released([&](std::stop_token) { return cp::read_step(path, o); });
    py::list faces;
    for (std::size_t i = 0; i < p.cad.faces.faces.size(); ++i) {
        const cp::cad_face& f = p.cad.faces.faces[i];
        std::vector<std::int64_t> facets(f.facets.begin(), f.facets.end());
        const std::size_t n = facets.size();
        faces.append(py::dict(py::arg("id") = i, py::arg("name") = f.name, py::arg("surface") = f.surface,
                              py::arg("area") = f.area, py::arg("deviation") = f.deviation,
                              py::arg("facets") = owned<std::int64_t>({n}, std::move(facets))));
    }
    std::vector<std::int64_t> face_of(p.cad.faces.face_of.begin(), p.cad.faces.face_of.end());
    const std::size_t n = face_of.size();
    py::dict cad(py::arg("unit") = p.cad.unit, py::arg("deflection") = p.cad.deflection,
                 py::arg("angular_deflection") = p.cad.angular_deflection,
                 py::arg("dropped_triangles") = p.cad.dropped_triangles, py::arg("faces") = faces,
                 py::arg("face_of") = owned<std::int64_t>({n}, std::move(face_of)));
    return py::make_tuple(std::make_shared<cp::triangle_mesh>(std::move(p.mesh)), cad);
#else
    (void)deflection, (void)angular_deflection;
    throw cp::io_error(path, path + ": a STEP file, and this build of certipose reads no STEP (OpenCASCADE was not "
                                    "found when it was built: Debian libocct-data-exchange-dev); give a mesh or rebuild");
#endif
}

/// A certipose-part folder's boxes as arrays and its summary.json as text.
py::tuple read_part(const std::string& folder) {
    std::vector<std::int64_t> facets;
    std::vector<double> bounds;
    std::vector<std::uint8_t> classes;
    std::vector<std::int8_t> reasons;
    const std::filesystem::path dir(folder);
    const std::string summary = run_released([&](std::stop_token) {
        const cp::part_summary run = cp::read_part_summary(dir);
        cp::read_part_boxes(dir, run.settings.box_store, [&](const cp::part_box& b) {
            facets.push_back(static_cast<std::int64_t>(b.facet));
            for (std::size_t k = 0; k < 3; ++k) bounds.insert(bounds.end(), b.box.position[k].begin(), b.box.position[k].end());
            for (std::size_t k = 0; k < 3; ++k) bounds.insert(bounds.end(), b.box.orientation[k].begin(), b.box.orientation[k].end());
            classes.push_back(b.box.cls == cp::box_class::valid ? 0 : 1);
            reasons.push_back(b.box.reason ? static_cast<std::int8_t>(*b.box.reason) : std::int8_t{-1});
        });
        return cp::detail::json_io::read_text_file(dir / "summary.json", "read_part");
    });
    const std::size_t n = facets.size();
    return py::make_tuple(owned<std::int64_t>({n}, std::move(facets)), owned<double>({n, 6, 2}, std::move(bounds)),
                          owned<std::uint8_t>({n}, std::move(classes)), owned<std::int8_t>({n}, std::move(reasons)), summary);
}

}  // namespace

PYBIND11_MODULE(_core, m) {
    m.doc() = "certipose's compiled core; use the package `certipose` (docs/python.md).";
    py::register_exception_translator(&translate);

    py::class_<cp::triangle_mesh, std::shared_ptr<cp::triangle_mesh>>(m, "Mesh")
        .def(py::init([](const py::object& vertices, const py::object& faces) {
                 const py::array v = py::array::ensure(vertices), f = py::array::ensure(faces);
                 if (!v) throw cp::invalid_argument("vertices", "Mesh: vertices must be an (N, 3) array of numbers");
                 if (!f) throw cp::invalid_argument("faces", "Mesh: faces must be an (M, 3) array of integer vertex indices");
                 // Face indices are integers: a float array would be truncated in silence by a cast.
                 const char kind = f.dtype().kind();
                 if (f.size() > 0 && kind != 'i' && kind != 'u')
                     throw cp::invalid_argument("faces", "Mesh: faces must be integer vertex indices, got an array of dtype " +
                                                             py::str(f.dtype()).cast<std::string>());
                 const char vkind = v.dtype().kind();
                 if (vkind != 'f' && vkind != 'i' && vkind != 'u')
                     throw cp::invalid_argument("vertices", "Mesh: vertices must be numbers, got an array of dtype " +
                                                                py::str(v.dtype()).cast<std::string>());
                 if (v.dtype().is(py::dtype::of<float>()) &&
                     PyErr_WarnEx(PyExc_UserWarning,
                                  "Mesh: the vertices are float32; they are widened to float64 as they are, so the "
                                  "boxes are those of the float32 part (about 1e-8 m from a double-precision file's), "
                                  "and the digest is not the file's: pass float64 vertices (e.g. "
                                  "numpy.asarray(mesh.vertices, dtype=float) from the source's own doubles)",
                                  1) != 0)
                     throw py::error_already_set();
                 using doubles = py::array_t<double, py::array::c_style | py::array::forcecast>;
                 using indices = py::array_t<std::int64_t, py::array::c_style | py::array::forcecast>;
                 return std::const_pointer_cast<cp::triangle_mesh>(mesh_from_arrays(doubles::ensure(v), indices::ensure(f)));
             }),
             py::arg("vertices"), py::arg("faces"))
        .def_static(
            "read",
            [](const std::string& path, double scale, std::optional<double> weld) {
                if (cp::is_step_path(path)) {  // in metres, at the default tessellation
                    if (scale != 1.0)
                        throw cp::invalid_argument("scale", path + " is a STEP file, which carries its length unit "
                                                                   "(it is read in metres); scale is for meshes");
                    if (weld)
                        throw cp::invalid_argument("weld_tolerance", path + " is a STEP file: its tessellation is "
                                                                            "welded exactly; weld_tolerance is for meshes");
                    return read_step(path, std::nullopt, std::nullopt)[0]
                        .cast<std::shared_ptr<cp::triangle_mesh>>();
                }
                cp::read_options o;
                o.scale = scale;
                o.weld_tolerance = weld;
                return std::make_shared<cp::triangle_mesh>(run_released([&](std::stop_token) { return cp::read_mesh(path, o); }));
            },
            py::arg("path"), py::arg("scale") = 1.0, py::arg("weld_tolerance") = py::none())
        .def_property_readonly("num_faces", &cp::triangle_mesh::num_faces, "The number of facets (triangles).")
        .def_property_readonly("num_vertices", &cp::triangle_mesh::num_vertices, "The number of vertices.")
        .def_property_readonly("vertices",
                               [](py::object self) {
                                   const auto& m = self.cast<const cp::triangle_mesh&>();
                                   py::array_t<double> a({m.num_vertices(), std::size_t{3}}, {sizeof(Eigen::Vector3d), sizeof(double)},
                                                         m.vertices().data()->data(), self);
                                   py::detail::array_proxy(a.ptr())->flags &= ~py::detail::npy_api::NPY_ARRAY_WRITEABLE_;
                                   return a;
                               },
                               "The (N, 3) float64 vertex coordinates in metres (read-only, no copy).")
        .def_property_readonly("faces",
                               [](py::object self) {
                                   const auto& m = self.cast<const cp::triangle_mesh&>();
                                   py::array_t<std::uint32_t> a({m.num_faces(), std::size_t{3}}, m.faces().data()->data(), self);
                                   py::detail::array_proxy(a.ptr())->flags &= ~py::detail::npy_api::NPY_ARRAY_WRITEABLE_;
                                   return a;
                               },
                               "The (M, 3) uint32 vertex indices of each facet (read-only, no copy).")
        .def("facet",
             [](const cp::triangle_mesh& m, std::size_t i) {
                 const cp::facet& f = m.facet(i);
                 py::array_t<double> v({3, 3});
                 auto w = v.mutable_unchecked<2>();
                 for (int r = 0; r < 3; ++r)
                     for (int k = 0; k < 3; ++k) w(r, k) = f.v[r][k];
                 return py::dict(py::arg("vertices") = v,
                                 py::arg("normal") = std::array<double, 3>{f.normal[0], f.normal[1], f.normal[2]},
                                 py::arg("centroid") = std::array<double, 3>{f.centroid[0], f.centroid[1], f.centroid[2]},
                                 py::arg("area") = f.area);
             },
             py::arg("i"),
             "Facet i as the solver sees it: a dict of \"vertices\" (3 x 3, metres), \"normal\" (unit, outward), "
             "\"centroid\" and \"area\" (m^2).")
        .def_property_readonly("areas",
                               [](const cp::triangle_mesh& m) {
                                   std::vector<double> a(m.num_faces());
                                   for (std::size_t i = 0; i < a.size(); ++i) a[i] = m.facet(i).area;
                                   const std::size_t n = a.size();
                                   return owned<double>({n}, std::move(a));
                               },
                               "Each facet's area (m^2), as an (M,) float64 array.")
        .def_property_readonly("digest", [](const cp::triangle_mesh& m) { return cp::mesh_digest(m); },
                               "The mesh's fingerprint, as the programs record it in summary.json and PLAN.json.");

    py::class_<camera_spec>(m, "Camera")
        .def_static("from_json", &camera_from_json, py::arg("text"), py::arg("source") = "", py::arg("base_dir") = "",
                    "A camera from the camera JSON's text; `source` names it in errors, `base_dir` resolves the "
                    "relative paths it holds (a calibration file).")
        .def_static("read", &camera_from_file, py::arg("path"), py::arg("working_distance") = py::none(),
                    py::arg("min_view_angle") = py::none(),
                    "A camera from our camera JSON file or an OpenCV/ROS calibration file (then `working_distance` "
                    "(d_min, d_max) in metres and `min_view_angle` in radians are required); certipose.camera() "
                    "calls it.")
        .def("to_json", [](const camera_spec& c) { return cp::camera_task_to_json(c.input).dump(); },
             "The camera and task as the camera JSON's text (what to_dict() parses).")
        .def_property_readonly("model", [](const camera_spec& c) { return std::string(cp::model_name(c.input.camera)); },
                               "The camera model as the camera JSON names it: \"thin_lens\" or \"pinhole\".")
        .def_property_readonly("distance_range", [](const camera_spec& c) {
            const cp::distance_range r = cp::capped_distance_range(c.input.calibrated(), c.input.task.max_metres_per_pixel);
            return std::pair<double, double>(r.min, r.max);
        }, "(nearest, farthest) distance in metres at which a point is in focus and resolved finely enough.");

    py::class_<facet_settings>(m, "FacetSettings")
        .def(py::init<>())
        .def_readwrite("position_eps", &facet_settings::position_eps)
        .def_readwrite("orientation_eps", &facet_settings::orientation_eps)
        .def_readwrite("max_boxes", &facet_settings::max_boxes)
        .def_readwrite("time_limit", &facet_settings::time_limit)
        .def_readwrite("refine", &facet_settings::refine)
        .def_readwrite("corner_depth", &facet_settings::corner_depth)
        .def_readwrite("corner_rest", &facet_settings::corner_rest)
        .def_readwrite("paper_paving", &facet_settings::paper_paving)
        .def_readwrite("grow", &facet_settings::grow);

    py::class_<facet_result>(m, "FacetArrays")
        .def_readonly("facet", &facet_result::facet)
        .def_property_readonly("bounds", [](const facet_result& r) { return r.boxes.bounds; })
        .def_property_readonly("class_codes", [](const facet_result& r) { return r.boxes.classes; })
        .def_property_readonly("reason_codes", [](const facet_result& r) { return r.boxes.reasons; })
        .def_readonly("stats", &facet_result::stats)
        .def_readonly("record", &facet_result::record);

    py::class_<solver, std::shared_ptr<solver>>(m, "Solver")
        .def(py::init([](std::shared_ptr<cp::triangle_mesh> mesh, camera_spec camera, const std::string& occlusion,
                         const std::string& semantics,
                         const std::vector<std::tuple<std::shared_ptr<cp::triangle_mesh>, std::string, double>>& occluders,
                         const std::vector<std::string>& keep_in, const std::vector<std::string>& keep_out) {
                 return std::make_shared<solver>(std::move(mesh), std::move(camera), occlusion, semantics, occluders, keep_in,
                                                 keep_out);
             }),
             py::arg("mesh"), py::arg("camera"), py::arg("occlusion") = "aabb", py::arg("mesh_semantics") = "auto",
             py::arg("occluders") = std::vector<std::tuple<std::shared_ptr<cp::triangle_mesh>, std::string, double>>{},
             py::arg("keep_in") = std::vector<std::string>{}, py::arg("keep_out") = std::vector<std::string>{})
        .def_property_readonly("occlusion", &solver::occlusion)
        .def_property_readonly("survey", &solver::survey)
        .def_property_readonly("camera_json", [](const solver& s) { return cp::camera_task_to_json(s.camera()).dump(); })
        .def("solve_facet", &solver::solve_facet, py::arg("facet"), py::arg("settings"))
        .def("start_part", &start_part, py::arg("settings"), py::arg("facets") = py::none(), py::arg("threads") = 0,
             py::arg("boundary") = false, py::arg("keep_largest") = py::none(), py::arg("max_boxes") = py::none(),
             py::arg("time_limit") = py::none(), py::arg("reuse") = true, py::arg("progress") = py::none(),
             py::arg("collect") = false)
        .def("inspect", &inspect, py::arg("bounds"), py::arg("threads") = 0, py::arg("possible") = true);

    py::class_<plan_holder>(m, "PlanDocument")
        .def_static("read", [](const std::string& path) { return plan_holder{cp::read_plan(path)}; }, py::arg("path"))
        .def_static("from_json", [](const std::string& text) {
            return plan_holder{cp::plan_from_json(cp::detail::json_io::parse(text, "plan"), "plan")};
        })
        .def("to_json", [](const plan_holder& p) { return cp::json_text(cp::plan_to_json(p.doc)); })
        .def("write", [](const plan_holder& p, const std::string& path) { write_atomically(path, cp::json_text(cp::plan_to_json(p.doc))); })
        .def("export", [](const plan_holder& p, const std::string& format, std::shared_ptr<cp::triangle_mesh> mesh,
                          const std::string& parent_frame, const std::string& link, const std::string& title,
                          const std::string& link_prefix, const std::string& robot_name, bool snippet) {
            return export_plan(p.doc, format, std::move(mesh), parent_frame, link, title, link_prefix, robot_name, snippet);
        }, py::arg("format"), py::arg("mesh") = nullptr, py::arg("parent_frame") = "world", py::arg("link") = "optical",
           py::arg("title") = "certipose plan", py::arg("link_prefix") = "camera_", py::arg("robot_name") = "certipose_cameras",
           py::arg("snippet") = false)
        .def_readonly("seconds_inspection", &plan_holder::seconds_inspection)
        .def_readonly("seconds_choice", &plan_holder::seconds_choice)
        .def_readonly("exact", &plan_holder::exact);

    m.def("plan_options", &plan_options_of, py::arg("cameras"), py::arg("coverage"), py::arg("tolerance"), py::arg("lp_seconds"),
          py::arg("exact_seconds"), py::arg("threads"), py::arg("all_candidates"));
    py::class_<cp::plan_options>(m, "PlanOptions");
    m.def("make_plan", &make_plan_py, py::arg("solver"), py::arg("source"), py::arg("per_facet"), py::arg("trusted"),
          py::arg("mesh_path"), py::arg("scale"), py::arg("options"), py::arg("progress"));
    m.def("verify", &verify_py, py::arg("solver"), py::arg("poses"), py::arg("tolerance"), py::arg("progress"));
    m.def("read_part", &read_part, py::arg("folder"));
    m.def("read_step", &read_step, py::arg("path"), py::arg("deflection") = py::none(), py::arg("angular_deflection") = py::none());
    m.def("run_record", &run_record_json, py::arg("solver"));
    m.def("write_atomically", [](const std::string& path, py::bytes content) { write_atomically(path, std::string(content)); });
    m.attr("has_viewer") = !certipose_viewer_script.empty();
    m.attr("version") = CERTIPOSE_VERSION;
    m.attr("example_camera") = std::string(certipose_example_camera);
    m.def("sample_part", [] { return std::make_shared<cp::triangle_mesh>(cp::make_sample_part().mesh); });

    py::class_<part_run>(m, "PartRun")
        .def("__iter__", [](py::object self) { return self; })
        .def("__next__",
             [](part_run& r) {
                 auto f = r.next();
                 if (!f) throw py::stop_iteration();
                 return std::move(*f);
             })
        .def("collect", &part_run::collect)
        .def("cancel", &part_run::cancel)
        .def_property_readonly("summary", &part_run::summary);

    m.attr("boundary_reasons") = [] {
        py::list l;
        for (std::size_t k = 0; k < cp::boundary_reason_count; ++k)
            l.append(std::string(cp::to_string(static_cast<cp::boundary_reason>(k))));
        return l;
    }();
}
