// libFuzzer harness of the result-document reader (certipose-solve's result JSON, docs/io.md):
// parse_result_json returns a document that writes back out, or throws a certipose::error.
#include "harness.hpp"

#include <certipose/io/json.hpp>

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    certipose_fuzz::accept_certipose_errors([&] {
        const certipose::result_document d = certipose::parse_result_json(certipose_fuzz::text(data, size), "fuzz.json");
        (void)certipose::result_to_json(d).dump();
    });
    return 0;
}
