// certipose/io/output_files.hpp — all the output files of one run, committed together or not at
// all, never over an input (no CGAL, no JSON library).
//
// A program that writes several files (a result JSON and a PLY; a part run's summary.json and
// boxes.jsonl) stages each one first — a complete temporary file next to its target, written
// and flushed — and only when every one of them exists renames them all onto their targets
// (`commit`). So a file that cannot be written (missing directory, no permission, disk full)
// fails before any target is touched, and an interrupted or failed run leaves the old files as
// they were and no temporary behind (the destructor removes what was not committed). Large
// outputs are streamed (`stream`) into their temporary file as they are produced.
//
// `refuse_overwriting_inputs(inputs, outputs)` is the check every program runs first: an output
// that is an input under another name (`./part.off`, a symlink, a hard link) is refused with one
// clear line, compared by `std::filesystem::equivalent` when both exist and by weakly canonical
// paths otherwise; so are two outputs that are the same file.
#pragma once

#include "certipose/error.hpp"
#include "certipose/io/write_file.hpp"

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <memory>
#include <string>
#include <string_view>
#include <system_error>
#include <utility>
#include <vector>

#if defined(__unix__) || defined(__APPLE__)
#include <fcntl.h>
#include <unistd.h>
#endif

namespace certipose {

namespace detail::io {

/// Same file? `equivalent` when both exist (hard links, symlinks), weakly canonical paths
/// otherwise (an output that does not exist yet, `./x` against `x`).
inline bool same_file(const std::filesystem::path& a, const std::filesystem::path& b) {
    namespace fs = std::filesystem;
    std::error_code ea, eb, ec;
    if (fs::exists(a, ea) && fs::exists(b, eb)) {
        const bool same = fs::equivalent(a, b, ec);
        if (!ec) return same;
    }
    const fs::path ca = fs::weakly_canonical(a, ea), cb = fs::weakly_canonical(b, eb);
    if (ea || eb) return fs::absolute(a).lexically_normal() == fs::absolute(b).lexically_normal();
    return ca == cb;
}

}  // namespace detail::io

/// A named path for messages: what the user called it ("--out") and the path.
struct named_path {
    std::string what;
    std::filesystem::path path;
};

/// Throws invalid_argument(output.what) when an output names an input or another output.
inline void refuse_overwriting_inputs(const std::vector<named_path>& inputs, const std::vector<named_path>& outputs) {
    for (std::size_t i = 0; i < outputs.size(); ++i) {
        const auto& o = outputs[i];
        for (const auto& in : inputs)
            if (detail::io::same_file(o.path, in.path))
                throw invalid_argument(o.what, o.what + " " + o.path.string() + " is the input " + in.what + " " +
                                                   in.path.string() + "; refusing to overwrite an input");
        for (std::size_t j = 0; j < i; ++j)
            if (detail::io::same_file(o.path, outputs[j].path))
                throw invalid_argument(o.what, o.what + " " + o.path.string() + " is the same file as " +
                                                   outputs[j].what + " " + outputs[j].path.string());
    }
}

/// The output files of one run (see the header comment). Not thread-safe; one per run.
class output_files {
public:
    output_files() = default;
    output_files(const output_files&) = delete;
    output_files& operator=(const output_files&) = delete;
    ~output_files() { discard(); }

    /// Stages `content` for `target`: the temporary file is complete when this returns.
    /// Throws io_error(target) if it cannot be written (nothing of this run is committed then).
    void add(const std::filesystem::path& target, std::string_view content) {
        staged& s = open(target);
        s.out.write(content.data(), static_cast<std::streamsize>(content.size()));
        finish(s);
    }

    /// Opens `target`'s temporary file for streaming; write to the returned stream, then call
    /// `close(target)` (or `commit`, which closes every stream).
    /// Asking again for the same target returns the same stream (one temporary per target).
    std::ostream& stream(const std::filesystem::path& target) {
        for (auto& s : staged_)
            if (s->target == target && s->out.is_open()) return s->out;
        return open(target).out;
    }

    /// Flushes and closes `target`'s stream; throws io_error(target) on a write error.
    void close(const std::filesystem::path& target) {
        for (auto& s : staged_)
            if (s->target == target && s->out.is_open()) finish(*s);
    }

    /// Renames every staged file onto its target, in the order staged. Throws io_error naming
    /// the file that could not be closed or renamed; the files not yet renamed are removed.
    void commit() {
        for (auto& s : staged_)
            if (s->out.is_open()) finish(*s);
        for (auto& s : staged_) {
            std::error_code ec;
            std::filesystem::rename(s->tmp, s->target, ec);
            if (ec)
                throw io_error(s->target.string(), "cannot write " + s->target.string() +
                                                       ": cannot rename the temporary file onto it (" + ec.message() + ")");
            s->committed = true;
        }
        staged_.clear();
    }

    /// Removes every temporary file not committed (also done by the destructor).
    void discard() noexcept {
        for (auto& s : staged_) {
            if (s->committed) continue;
            if (s->out.is_open()) s->out.close();
            std::error_code ignored;
            std::filesystem::remove(s->tmp, ignored);
        }
        staged_.clear();
    }

    /// The temporary files staged so far (e.g. for a signal handler's last-resort cleanup).
    std::vector<std::filesystem::path> temporaries() const {
        std::vector<std::filesystem::path> t;
        for (const auto& s : staged_) t.push_back(s->tmp);
        return t;
    }

private:
    struct staged {
        std::filesystem::path target, tmp;
        std::ofstream out;
        bool committed = false;
    };

    staged& open(const std::filesystem::path& target) {
        const std::string name = target.string();
        if (target.empty() || !target.has_filename()) throw io_error(name, "cannot write '" + name + "': not a file name");
        std::error_code ec;
        if (std::filesystem::is_directory(target, ec))
            throw io_error(name, "cannot write " + name + ": it is a directory");
        auto s = std::make_unique<staged>();
        s->target = target;
        s->tmp = detail::io::temporary_sibling(target);
        s->out.open(s->tmp, std::ios::binary | std::ios::trunc);
        if (!s->out) {
            const std::filesystem::path dir = target.parent_path();
            throw io_error(name, "cannot write " + name + ": cannot create a file in '" +
                                     (dir.empty() ? std::string(".") : dir.string()) + "'");
        }
        staged_.push_back(std::move(s));
        return *staged_.back();
    }

    void finish(staged& s) {
        s.out.flush();
        const bool ok = static_cast<bool>(s.out);
        s.out.close();
        if (!ok || s.out.fail())
            throw io_error(s.target.string(), "cannot write " + s.target.string() + ": write failed (disk full?)");
#if defined(__unix__) || defined(__APPLE__)
        // Durable before the rename publishes it (write_file.hpp says why).
        if (const int fd = ::open(s.tmp.c_str(), O_RDONLY | O_CLOEXEC); fd >= 0) {
            (void)::fsync(fd);
            ::close(fd);
        }
#endif
    }

    std::vector<std::unique_ptr<staged>> staged_;
};

}  // namespace certipose
