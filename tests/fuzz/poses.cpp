// libFuzzer harness of the POSES.json reader (certipose-verify; io/plan_files.hpp): poses_from_json
// returns poses with finite, ordered bounds, or throws a certipose::error.
#include "harness.hpp"

#include <certipose/io/plan_files.hpp>

#include <cmath>
#include <cstdlib>

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    certipose_fuzz::accept_certipose_errors([&] {
        const auto poses = certipose::poses_from_json(
            certipose::detail::json_io::parse(certipose_fuzz::text(data, size), "fuzz.json"));
        for (const auto& p : poses)
            for (const auto* b : {&p.position, &p.orientation})
                for (const auto& c : *b)
                    if (!(c[0] <= c[1])) std::abort();  // the reader promised ordered bounds
    });
    return 0;
}
