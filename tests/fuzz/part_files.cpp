// libFuzzer harness of the whole-part output readers (docs/part.md, certipose-part): the bytes are
// read as a summary.json (part_summary_from_json) and as a boxes.jsonl file (read_boxes_jsonl,
// which reads line by line from a file); each returns what it read or throws a certipose::error.
#include "harness.hpp"

#include <certipose/io/json.hpp>
#include <certipose/io/part_files.hpp>

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    static const certipose_fuzz::scratch_file file("boxes.jsonl");
    certipose_fuzz::accept_certipose_errors([&] {
        const auto j = certipose::detail::json_io::parse(certipose_fuzz::text(data, size), "summary.json");
        (void)certipose::part_summary_to_json(certipose::part_summary_from_json(j)).dump();
    });
    const auto& path = file.write(data, size);
    certipose_fuzz::accept_certipose_errors([&] {
        certipose::read_boxes_jsonl(path, [](const certipose::part_box& b) {
            certipose_fuzz::require(b.box.cls == certipose::box_class::valid || b.box.cls == certipose::box_class::boundary);
        });
    });
    return 0;
}
