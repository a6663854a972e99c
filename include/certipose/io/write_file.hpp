// certipose/io/write_file.hpp — replace a file's content all at once or not at all (no CGAL,
// no JSON library).
//
// `write_file_atomically(path, content)` is how every certipose writer (result JSON, PLY) puts
// files on disk: the content goes to a new temporary file in the SAME directory as `path`
// (a rename is only atomic within one file system), is flushed to the device (fsync), and is
// then renamed over `path`. A reader therefore sees the old file or the complete new one, never
// a half-written one, even if the program is killed or the disk fills mid-write; on failure the
// temporary file is removed and certipose::io_error names the path and the system's reason.
// POSIX calls are used where available (open/write/fsync); elsewhere a flushed std::ofstream
// and std::filesystem::rename give the same "all or nothing" without the durability flush.
#pragma once

#include "certipose/error.hpp"

#include <atomic>
#include <cerrno>
#include <chrono>
#include <cstddef>
#include <filesystem>
#include <string>
#include <string_view>
#include <system_error>

#if defined(__unix__) || defined(__APPLE__)
#include <fcntl.h>
#include <unistd.h>
#define CERTIPOSE_IO_POSIX 1
#else
#include <fstream>
#endif

namespace certipose {

namespace detail::io {

inline std::string errno_text(int err) { return std::generic_category().message(err); }

/// A name no other writer (thread or process) picks: ".<name>.tmp-<pid>-<counter>-<clock>".
/// Hidden (leading dot) so a directory listing during the write does not show it as a result.
inline std::filesystem::path temporary_sibling(const std::filesystem::path& target) {
    static std::atomic<unsigned long> counter{0};
#ifdef CERTIPOSE_IO_POSIX
    const long pid = static_cast<long>(::getpid());
#else
    const long pid = 0;
#endif
    const auto tick = std::chrono::steady_clock::now().time_since_epoch().count();
    std::string name = "." + target.filename().string() + ".tmp-" + std::to_string(pid) + "-" +
                       std::to_string(counter.fetch_add(1)) + "-" + std::to_string(tick);
    return target.parent_path() / name;
}

}  // namespace detail::io

/// Replaces the content of `path` by `content` atomically (see the header comment): afterwards
/// `path` holds exactly `content`, or — when this throws certipose::io_error(path) — it is
/// unchanged (or still absent) and no temporary file is left behind. Fails when the directory
/// does not exist or is not writable, when `path` names a directory, or on any write error.
inline void write_file_atomically(const std::filesystem::path& path, std::string_view content) {
    namespace fs = std::filesystem;
    const std::string name = path.string();
    const std::string who = "write_file_atomically: ";
    if (path.empty() || !path.has_filename())
        throw io_error(name, who + "not a file name: '" + name + "'");
    const fs::path dir = path.parent_path();
    const std::string dir_name = dir.empty() ? std::string(".") : dir.string();

#ifdef CERTIPOSE_IO_POSIX
    fs::path tmp;
    int fd = -1;
    for (int attempt = 0; attempt < 16 && fd < 0; ++attempt) {
        tmp = detail::io::temporary_sibling(path);
        // O_EXCL: never reuse an existing file; mode 0666 is then reduced by the umask, so the
        // result gets the same permissions an ordinary std::ofstream would give it.
        fd = ::open(tmp.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, 0666);
        if (fd < 0 && errno != EEXIST && errno != EINTR) break;
    }
    if (fd < 0) {
        const int err = errno;
        throw io_error(name, who + "cannot write " + name + ": cannot create a file in '" +
                                 dir_name + "': " + detail::io::errno_text(err));
    }
    const auto fail = [&](const std::string& what, int err) {
        if (fd >= 0) ::close(fd);
        std::error_code ignored;
        fs::remove(tmp, ignored);
        throw io_error(name, who + "cannot write " + name + ": " + what +
                                 (err != 0 ? ": " + detail::io::errno_text(err) : std::string()));
    };
    std::size_t done = 0;
    while (done < content.size()) {
        const ::ssize_t n = ::write(fd, content.data() + done, content.size() - done);
        if (n < 0) {
            if (errno == EINTR) continue;
            fail("write failed", errno);
        }
        done += static_cast<std::size_t>(n);
    }
    // Flush to the device before the rename publishes the file: after a crash the new name
    // must not point at a file whose data never reached the disk.
    if (::fsync(fd) != 0 && errno != EINVAL && errno != EROFS) fail("fsync failed", errno);
    const int fd_closed = fd;
    fd = -1;
    if (::close(fd_closed) != 0 && errno != EINTR) fail("close failed", errno);
    std::error_code ec;
    fs::rename(tmp, path, ec);
    if (ec) fail("cannot rename the temporary file onto it (" + ec.message() + ")", 0);
    // Make the rename itself durable; best effort (some file systems refuse fsync on a dir).
    if (const int dfd = ::open(dir_name.c_str(), O_RDONLY | O_CLOEXEC); dfd >= 0) {
        (void)::fsync(dfd);
        ::close(dfd);
    }
#else
    const fs::path tmp = detail::io::temporary_sibling(path);
    std::error_code ec;
    const auto fail = [&](const std::string& what) {
        std::error_code ignored;
        fs::remove(tmp, ignored);
        throw io_error(name, who + "cannot write " + name + ": " + what);
    };
    {
        std::ofstream out(tmp, std::ios::binary | std::ios::trunc);
        if (!out) fail("cannot create a file in '" + dir_name + "'");
        out.write(content.data(), static_cast<std::streamsize>(content.size()));
        out.flush();
        if (!out) fail("write failed");
    }
    fs::rename(tmp, path, ec);
    if (ec) fail("cannot rename the temporary file onto it (" + ec.message() + ")");
#endif
}

}  // namespace certipose

#undef CERTIPOSE_IO_POSIX
