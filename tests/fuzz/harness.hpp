// tests/fuzz/harness.hpp — what every libFuzzer harness of certipose's readers shares.
//
// The contract each harness checks (issue: hostile inputs): a reader given any bytes either
// returns a valid object or throws a certipose::error. Any other exception escapes
// LLVMFuzzerTestOneInput and aborts (libFuzzer reports it as a crash, with the input saved);
// AddressSanitizer, UBSan and LeakSanitizer report memory errors, undefined behaviour and leaks.
// Readers that only take a path get the bytes through a file in a per-process temporary folder.
#pragma once

#include <certipose/error.hpp>

#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>
#include <string_view>

#include <unistd.h>

namespace certipose_fuzz {

inline std::string_view text(const std::uint8_t* data, std::size_t size) {
    return {reinterpret_cast<const char*>(data), size};
}

/// `name` in a folder of this process's own, rewritten with `data` on every call; the folder
/// goes when the process exits normally.
class scratch_file {
public:
    explicit scratch_file(const std::string& name)
        : dir_(std::filesystem::temp_directory_path() / ("certipose-fuzz-" + std::to_string(::getpid()))),
          path_(dir_ / name) {
        std::filesystem::create_directories(dir_);
    }
    scratch_file(const scratch_file&) = delete;
    scratch_file& operator=(const scratch_file&) = delete;
    ~scratch_file() {
        std::error_code ec;
        std::filesystem::remove_all(dir_, ec);
    }
    const std::filesystem::path& write(const std::uint8_t* data, std::size_t size) const {
        std::ofstream out(path_, std::ios::binary | std::ios::trunc);
        out.write(reinterpret_cast<const char*>(data), static_cast<std::streamsize>(size));
        out.close();
        if (!out) std::abort();  // the harness itself failed, not the reader
        return path_;
    }

private:
    std::filesystem::path dir_, path_;
};

/// Runs `read`; a certipose::error is an accepted answer, anything else is not.
template <class F>
void accept_certipose_errors(F&& read) {
    try {
        read();
    } catch (const certipose::error&) {
        // the contract: a typed error with a message
    }
}

/// A property the returned object must have: a broken one is a crash.
inline void require(bool ok) {
    if (!ok) std::abort();
}

}  // namespace certipose_fuzz
