// certipose/io/run_journal.hpp — a whole-part run that survives a kill (docs/part.md, "Runs that
// survive a kill"). Needs nlohmann-json and Boost (CRC).
//
// While certipose-part runs, its box stores grow in DIR/run-in-progress/ (boxes.cpbx,
// boxes.jsonl), beside `settings.json` (what changes the answer: the mesh's digest, the camera,
// the task, every solver setting, the scene) and `journal`. At checkpoints (every second or every
// 32 facets, whichever comes first) the stores are flushed and made durable (fsync), and only
// then one journal line is appended and made durable: the facets finished since the last line,
// and how many bytes of each store hold every facet up to them. So any journal line that reaches
// the disk names store bytes that are already there, whatever ends the process: SIGKILL, a power
// loss, a full disk.
//
// A journal line is `<CRC-32 of the JSON, 8 hex digits> <JSON>\n`, the JSON being
// {"facets": [summary.json facet records], "bytes": {"boxes.cpbx": N, ...}, "seconds": S}
// (S: the run's wall time so far, over every invocation), or {"commit": true} when commit()
// begins (only then may resume take a store back from DIR). A line cut short or damaged fails its
// CRC; it and everything after it are dropped on resume.
//
// `resume` continues such a run: it refuses another run's settings (naming the first field that
// differs), keeps the facets of the good journal lines, cuts each store back to the bytes they
// name, and the program solves the rest of the selection. A run that SIGINT, SIGTERM, a deadline
// or a box budget ended was committed as usual (summary.json "termination" not "completed"):
// resume copies its stores back into DIR/run-in-progress and continues it the same way, so the
// committed folder stays readable until the resumed run commits. `commit` moves the stores onto
// DIR/boxes.*, writes summary.json atomically and removes the folder; a kill between those
// steps is resumed too (the stores are moved back).
#pragma once

#include <algorithm>

#include "certipose/error.hpp"
#include "certipose/io/json.hpp"
#include "certipose/io/output_files.hpp"
#include "certipose/io/part_files.hpp"
#include "certipose/io/write_file.hpp"

#include <boost/crc.hpp>
#include <nlohmann/json.hpp>

#include <chrono>
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <map>
#include <memory>
#include <optional>
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

/// What a resumed run must share with the run it continues: summary.json without the facets,
/// totals and survey (results), the mesh's path (a moved file of the same digest is the same
/// mesh), the run's time limit (a wall budget of each invocation) and its box budget (checked in
/// facet order over every invocation, so a larger one continues a run the smaller one stopped
/// exactly as an uninterrupted run with the larger one would).
inline nlohmann::json resume_key(const nlohmann::json& summary) {
    nlohmann::json k = summary;
    for (const char* result : {"facets", "totals", "survey"}) k.erase(result);
    if (k.contains("mesh") && k["mesh"].is_object()) k["mesh"].erase("path");
    if (k.contains("settings") && k["settings"].is_object())
        for (const char* budget : {"time_limit", "max_boxes"}) k["settings"].erase(budget);
    return k;
}

namespace detail::journal {

namespace fs = std::filesystem;

inline std::string crc_hex(std::string_view text) {
    boost::crc_32_type crc;
    crc.process_bytes(text.data(), text.size());
    char hex[9];
    std::snprintf(hex, sizeof hex, "%08x", static_cast<unsigned>(crc.checksum()));
    return hex;
}

/// "mesh.digest: 1f2e… in the run, 0a9b… here", for the first value of `now` that differs
/// from `then` (JSON Patch paths from nlohmann::json::diff, read as dotted keys).
inline std::string first_difference(const nlohmann::json& then, const nlohmann::json& now) {
    const nlohmann::json patch = nlohmann::json::diff(then, now);
    if (patch.empty()) return {};
    const nlohmann::json& op = patch.front();
    const std::string pointer = op.value("path", "");
    std::string name;
    for (char c : pointer.substr(pointer.empty() ? 0 : 1)) name += c == '/' ? '.' : c;
    const nlohmann::json::json_pointer at(pointer);
    const auto show = [&](const nlohmann::json& doc) {
        return doc.contains(at) ? doc.at(at).dump() : std::string("nothing");
    };
    return name + ": " + show(then) + " in the run, " + show(now) + " here";
}

/// fsync of a file or directory by path; throws io_error(what) when the file system reports a
/// failure (not when it cannot sync a directory at all).
inline void sync_path(const fs::path& p, const std::string& what, bool directory = false) {
#if defined(__unix__) || defined(__APPLE__)
    const int fd = ::open(p.c_str(), (directory ? O_DIRECTORY : 0) | O_RDONLY | O_CLOEXEC);
    if (fd < 0) {
        if (directory) return;
        throw io_error(what, what + ": cannot open it to make it durable (" + detail::io::errno_text(errno) + ")");
    }
    const int rc = ::fsync(fd);
    const int err = errno;
    ::close(fd);
    if (rc != 0 && !(directory && (err == EINVAL || err == EROFS)))
        throw io_error(what, what + ": cannot make it durable: " + detail::io::errno_text(err) + " (disk full?)");
#else
    (void)p, (void)what, (void)directory;
#endif
}

}  // namespace detail::journal

/// The journal of a part run in progress (see the header comment). One per run; not thread-safe
/// (the part solver's sink calls `record` from one thread at a time).
class part_run_journal {
public:
    /// The folder beside the outputs that holds a run in progress.
    static constexpr std::string_view folder_name = "run-in-progress";

    /// What earlier invocations finished (empty for a new run).
    struct progress {
        std::vector<facet_record> facets;  ///< finished and durable, in selection order
        double seconds = 0;                ///< their wall time, every invocation together
    };

    /// How `resume` found `dir`.
    enum class found : std::uint8_t { nothing, unfinished, complete };

    part_run_journal(const part_run_journal&) = delete;
    part_run_journal& operator=(const part_run_journal&) = delete;
    part_run_journal(part_run_journal&&) = default;
    part_run_journal& operator=(part_run_journal&&) = default;
    ~part_run_journal() = default;  // a run that fails leaves the folder for --resume

    /// A new run in `dir` writing the named stores: an unfinished run there is discarded.
    /// `key` is resume_key of the run's summary.
    static part_run_journal start(const std::filesystem::path& dir, const nlohmann::json& key,
                                  const std::vector<std::string>& stores) {
        part_run_journal j(dir);
        j.make_folder(key);
        for (const auto& s : stores) j.open_store(s, 0, true);
        j.open_journal(0);
        detail::journal::sync_path(j.folder_, j.folder_.string(), true);
        return j;
    }

    /// The run to continue in `dir`, if any, for a run whose resume_key is `key` writing the
    /// named stores: `found::unfinished` (returned in `journal`), `found::complete` (a committed
    /// run that finished: nothing to do) or `found::nothing`. Throws invalid_argument("--resume")
    /// naming the first setting that differs, and io_error for a store that is missing or
    /// shorter than its journal says.
    static found resume(const std::filesystem::path& dir, const nlohmann::json& key, const std::vector<std::string>& stores,
                        std::optional<part_run_journal>& journal) {
        namespace fs = std::filesystem;
        std::error_code ec;
        const fs::path folder = dir / folder_name;
        fs::remove_all(tombstone(dir), ec);
        const auto refuse_if_other = [&](const nlohmann::json& then, const std::string& what) {
            const std::string diff = detail::journal::first_difference(then, key);
            if (!diff.empty())
                throw invalid_argument("--resume", "--resume: " + what + " was made with other inputs or settings (" + diff +
                                                       "); run it with its own, or without --resume to start over");
        };
        const fs::path settings = folder / "settings.json";
        if (fs::is_directory(folder, ec) && fs::exists(settings, ec)) {
            refuse_if_other(detail::json_io::parse(detail::json_io::read_text_file(settings, "resume"), settings.string()),
                            "the unfinished run in " + folder.string());
            part_run_journal j(dir);
            const std::optional<line> last = j.read_journal();
            if (last) {  // else not one checkpoint (e.g. cut short copying a committed run): as below
                if (last->commit) {
                    // commit() removes DIR's summary before it moves a store, and writes its own
                    // after the last: a store moved and a summary there mean the commit is done.
                    bool moved = false;
                    for (const auto& s : stores) moved = moved || !fs::exists(folder / s, ec);
                    if (moved && fs::exists(dir / "summary.json", ec)) {
                        fs::remove_all(folder, ec);
                        return found::complete;
                    }
                }
                for (const auto& s : stores) {
                    const fs::path p = folder / s;
                    // A commit cut short between moving the stores (its marker is journaled first).
                    if (last->commit && !fs::exists(p, ec) && fs::exists(dir / s, ec)) fs::rename(dir / s, p, ec);
                    const auto want = last->bytes.find(s);
                    if (!fs::exists(p, ec) || want == last->bytes.end())
                        throw io_error(p.string(), "--resume: the unfinished run has no " + s + " (" + p.string() +
                                                       "); run without --resume to start over");
                    const auto size = fs::file_size(p, ec);
                    if (ec || size < want->second)
                        throw io_error(p.string(), "--resume: " + p.string() + " holds " + std::to_string(ec ? 0 : size) +
                                                       " bytes where the journal counts " + std::to_string(want->second) +
                                                       " (damaged); run without --resume to start over");
                    j.open_store(s, want->second, false);
                }
                journal.emplace(std::move(j));
                return found::unfinished;
            }
        }
        const fs::path summary_file = dir / "summary.json";
        if (!fs::exists(summary_file, ec)) return found::nothing;
        const nlohmann::json raw =
            detail::json_io::parse(detail::json_io::read_text_file(summary_file, "resume"), summary_file.string());
        refuse_if_other(resume_key(raw), "the run in " + dir.string());
        const part_summary s = part_summary_from_json(raw);
        if (s.totals.reason == termination::completed) return found::complete;
        // A committed run stopped early: its stores are copied, so it stays whole until this
        // one commits; the copies are durable before the journal line that names them.
        part_run_journal j(dir);
        j.make_folder(key);
        std::map<std::string, std::uint64_t> bytes;
        for (const auto& name : stores) {
            fs::copy_file(dir / name, folder / name, fs::copy_options::overwrite_existing, ec);
            const auto size = ec ? 0 : fs::file_size(folder / name, ec);
            if (ec)
                throw io_error((dir / name).string(), "--resume: cannot copy " + (dir / name).string() + " to continue it: " +
                                                          ec.message());
            bytes[name] = size;
            j.open_store(name, size, false);
            detail::journal::sync_path(folder / name, (folder / name).string());
        }
        j.open_journal(0);
        detail::journal::sync_path(folder, folder.string(), true);
        j.done_.facets = s.facets;
        j.done_.seconds = s.totals.seconds;
        j.pending_ = s.facets;
        j.append_line(bytes, s.totals.seconds);
        journal.emplace(std::move(j));
        return found::unfinished;
    }

    /// What earlier invocations finished.
    const progress& done() const noexcept { return done_; }

    /// The stream of store `name` (as given to start or resume), at its end.
    std::ostream& store(const std::string& name) {
        for (auto& s : stores_)
            if (s.name == name) return *s.out;
        throw invalid_argument("store", "part_run_journal: no store named " + name);
    }

    /// A facet finished: its boxes are in the stores. Checkpoints when one is due and
    /// `item_end` (the facet ends its work item: a patch's facets are journaled together, so
    /// that --resume continues between items and regroups the rest as the run would have).
    void record(const facet_record& r, bool item_end = true) {
        pending_.push_back(r);
        if (item_end && (pending_.size() >= checkpoint_facets || clock::now() - last_checkpoint_ >= checkpoint_interval))
            checkpoint();
    }

    /// Makes every facet recorded so far durable: the stores first, then one journal line.
    void checkpoint() {
        std::map<std::string, std::uint64_t> bytes;
        for (auto& s : stores_) {
            s.out->flush();
            if (!*s.out) throw io_error(s.name, s.name + ": write failed (disk full?)");
            bytes[s.name] = static_cast<std::uint64_t>(s.out->tellp());
            detail::journal::sync_path(s.path, s.path.string());
        }
        append_line(bytes, seconds());
    }

    /// The run's wall time so far, every invocation together.
    double seconds() const {
        return done_.seconds + std::chrono::duration<double>(clock::now() - started_).count();
    }

    /// Ends the run: makes everything durable, moves the stores onto `dir`/<name>, writes
    /// `summary` as `dir`/summary.json (atomically) and removes the folder. In that order, after
    /// a journaled commit marker: a kill before the summary is in place leaves no summary.json
    /// beside the new stores (an earlier run's is removed first), and --resume finishes the commit.
    void commit(std::string_view summary) {
        namespace fs = std::filesystem;
        checkpoint();
        output_files files;
        files.add(dir_ / "summary.json", summary);  // staged: a full disk fails here, nothing moved
        append_marker();
        for (auto& s : stores_) s.out->close();
        journal_.close();
        std::error_code ec;
        fs::remove(dir_ / "summary.json", ec);
        detail::journal::sync_path(dir_, dir_.string(), true);
        for (auto& s : stores_) {
            fs::rename(s.path, dir_ / s.name, ec);
            if (ec)
                throw io_error((dir_ / s.name).string(), "cannot write " + (dir_ / s.name).string() +
                                                             ": cannot move the store onto it (" + ec.message() + ")");
        }
        files.commit();
        detail::journal::sync_path(dir_, dir_.string(), true);
        // Out of resume's sight in one rename, then removed.
        fs::rename(folder_, tombstone(dir_), ec);
        fs::remove_all(ec ? folder_ : tombstone(dir_), ec);
    }

    /// The folder of the run in progress.
    const std::filesystem::path& folder() const noexcept { return folder_; }

    /// Facets per checkpoint at most, and time between checkpoints at most.
    static constexpr std::size_t checkpoint_facets = 32;
    static constexpr std::chrono::milliseconds checkpoint_interval{1000};

private:
    using clock = std::chrono::steady_clock;
    struct open_store_t {
        std::string name;
        std::filesystem::path path;
        std::unique_ptr<std::fstream> out;
    };
    struct line {
        std::map<std::string, std::uint64_t> bytes;
        bool commit = false;  ///< commit() began: its stores may already be in DIR
    };

    /// Where commit() moves the folder to remove it: resume and start ignore (and remove) it.
    static std::filesystem::path tombstone(const std::filesystem::path& dir) {
        return dir / (std::string(folder_name) + ".done");
    }

    /// A fresh folder (an unfinished run there removed) with the run's settings.
    void make_folder(const nlohmann::json& key) {
        std::error_code ec;
        std::filesystem::remove_all(folder_, ec);
        std::filesystem::remove_all(tombstone(dir_), ec);
        std::filesystem::create_directories(folder_, ec);
        if (ec) throw io_error(folder_.string(), "cannot create " + folder_.string() + ": " + ec.message());
        write_file_atomically(folder_ / "settings.json", key.dump(1) + "\n");
    }

    explicit part_run_journal(const std::filesystem::path& dir)
        : dir_(dir), folder_(dir / folder_name), started_(clock::now()), last_checkpoint_(started_) {}

    void open_store(const std::string& name, std::uint64_t keep, bool fresh) {
        open_store_t s{name, folder_ / name, nullptr};
        std::error_code ec;
        if (fresh) {
            std::ofstream create(s.path, std::ios::binary | std::ios::trunc);
            if (!create) throw io_error(s.path.string(), "cannot create " + s.path.string());
        } else {
            std::filesystem::resize_file(s.path, keep, ec);
            if (ec) throw io_error(s.path.string(), "--resume: cannot cut " + s.path.string() + " back: " + ec.message());
        }
        s.out = std::make_unique<std::fstream>(s.path, std::ios::binary | std::ios::in | std::ios::out);
        if (!*s.out) throw io_error(s.path.string(), "cannot open " + s.path.string());
        s.out->seekp(0, std::ios::end);
        stores_.push_back(std::move(s));
    }

    void open_journal(std::uint64_t keep) {
        const std::filesystem::path p = folder_ / "journal";
        {
            std::ofstream create(p, std::ios::binary | std::ios::app);
            if (!create) throw io_error(p.string(), "cannot create " + p.string());
        }
        std::error_code ec;
        std::filesystem::resize_file(p, keep, ec);
        if (ec) throw io_error(p.string(), "cannot cut " + p.string() + " back: " + ec.message());
        journal_.open(p, std::ios::binary | std::ios::app);
        if (!journal_) throw io_error(p.string(), "cannot open " + p.string());
    }

    /// Reads the journal's good lines into done_ (and cuts off what follows them); the last
    /// good line, or nothing when there is none.
    std::optional<line> read_journal() {
        const std::filesystem::path p = folder_ / "journal";
        std::ifstream in(p, std::ios::binary);
        std::optional<line> last;
        std::uint64_t good = 0;
        std::string text;
        while (in && std::getline(in, text)) {
            if (in.eof()) break;  // no newline: cut short
            if (text.size() < 10 || text[8] != ' ') break;
            const std::string_view body = std::string_view(text).substr(9);
            if (detail::journal::crc_hex(body) != text.substr(0, 8)) break;
            const nlohmann::json j = nlohmann::json::parse(body, nullptr, false);
            if (j.is_discarded() || !j.is_object()) break;
            try {
                if (j.contains("commit")) {
                    if (!last) break;
                    last->commit = true;
                } else {
                    line l;
                    for (const auto& [name, n] : j.at("bytes").items()) l.bytes[name] = n.get<std::uint64_t>();
                    std::vector<facet_record> facets;  // all of the line's, or none
                    const auto& list = j.at("facets");
                    for (std::size_t i = 0; i < list.size(); ++i)
                        facets.push_back(facet_record_from_json(list[i], "journal.facets[" + std::to_string(i) + "]"));
                    const double seconds = j.at("seconds").get<double>();
                    done_.facets.insert(done_.facets.end(), facets.begin(), facets.end());
                    done_.seconds = seconds;
                    last = std::move(l);
                }
            } catch (const std::exception&) {
                break;
            }
            good += text.size() + 1;
        }
        in.close();
        open_journal(good);
        return last;
    }

    void append_marker() {
        nlohmann::ordered_json j;
        j["commit"] = true;
        append_text(j.dump());
    }

    void append_line(const std::map<std::string, std::uint64_t>& bytes, double run_seconds) {
        nlohmann::ordered_json j;
        nlohmann::ordered_json facets = nlohmann::ordered_json::array();
        for (const auto& r : pending_) facets.push_back(facet_record_to_json(r));
        j["facets"] = std::move(facets);
        j["bytes"] = bytes;
        j["seconds"] = run_seconds;
        append_text(j.dump());
        pending_.clear();
        last_checkpoint_ = clock::now();
    }

    /// Appends one line, `<CRC> <body>`, and makes it durable.
    void append_text(const std::string& body) {
        const std::string text = detail::journal::crc_hex(body) + " " + body + "\n";
        journal_.write(text.data(), static_cast<std::streamsize>(text.size()));
        journal_.flush();
        const std::filesystem::path p = folder_ / "journal";
        if (!journal_) throw io_error(p.string(), p.string() + ": write failed (disk full?)");
        detail::journal::sync_path(p, p.string());
    }

    std::filesystem::path dir_, folder_;
    std::vector<open_store_t> stores_;
    std::ofstream journal_;
    progress done_;
    std::vector<facet_record> pending_;
    clock::time_point started_, last_checkpoint_;
};

/// A PartSink that hands each facet to `inner` (which writes the journal's stores) and then
/// records it in the journal. With `ends` (the run's work_plan::ends, in the order of the whole
/// run) and `done` (the facets earlier invocations finished), it checkpoints only between work
/// items.
template <class Inner>
struct journal_sink {
    Inner* inner;
    part_run_journal* journal;
    const std::vector<std::size_t>* ends = nullptr;
    std::size_t done = 0;
    template <class Outcome>
    void facet(const Outcome& o) {
        inner->facet(o);
        ++done;
        journal->record(o.record, !ends || std::binary_search(ends->begin(), ends->end(), done));
    }
};

}  // namespace certipose
