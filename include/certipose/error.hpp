// certipose/error.hpp — the library's one error hierarchy.
//
// Every exception certipose throws derives from certipose::error, so a caller can catch the
// whole library with one handler. Each subclass says what kind of input was wrong and the
// message names the offending field or value (e.g. "thin_lens_camera: focal_length must be
// positive, got -0.012"). Algorithms never throw for "no solution": a contractor proving a box
// infeasible returns an empty box, a paver with nothing valid returns an empty paving.
#pragma once

#include <cstddef>
#include <stdexcept>
#include <string>
#include <utility>

namespace certipose {

/// Root of every exception certipose throws.
class error : public std::runtime_error {
public:
    using std::runtime_error::runtime_error;
};

/// A parameter value is impossible (non-positive focal length, NaN threshold, ...).
/// `field()` names the parameter so tools can point at the offending input.
class invalid_argument : public error {
public:
    invalid_argument(std::string field, const std::string& what)
        : error(what), field_(std::move(field)) {}
    const std::string& field() const noexcept { return field_; }

private:
    std::string field_;
};

/// An index (facet id, dimension) outside its valid range.
class out_of_range : public error {
public:
    out_of_range(std::string field, std::size_t index, std::size_t size)
        : error(field + " " + std::to_string(index) + " is out of range (valid: 0.." +
                (size == 0 ? std::string("none") : std::to_string(size - 1)) + ")"),
          field_(std::move(field)), index_(index), size_(size) {}
    const std::string& field() const noexcept { return field_; }
    std::size_t index() const noexcept { return index_; }
    std::size_t size() const noexcept { return size_; }

private:
    std::string field_;
    std::size_t index_, size_;
};

/// A mesh the method cannot work on: empty, NaN/inf coordinates, degenerate faces,
/// non-manifold or open where a closed volume is required.
class mesh_error : public error {
public:
    using error::error;
};

/// A file that is missing, unreadable or unparsable. `path()` names it.
class io_error : public error {
public:
    io_error(std::string path, const std::string& what) : error(what), path_(std::move(path)) {}
    const std::string& path() const noexcept { return path_; }

private:
    std::string path_;
};

/// A geometric kernel (CGAL) reported failure where the method needs a result.
class geometry_error : public error {
public:
    using error::error;
};

}  // namespace certipose
