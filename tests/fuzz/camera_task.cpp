// libFuzzer harness of the camera/task JSON reader (docs/io.md): parse_camera_task
// returns a camera and a task whose values passed validation, or throws a certipose::error.
#include "harness.hpp"

#include <certipose/io/json.hpp>

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    certipose_fuzz::accept_certipose_errors([&] {
        const certipose::camera_task in = certipose::parse_camera_task(certipose_fuzz::text(data, size), "fuzz.json");
        in.task.validate();  // what came back is a task the solver accepts
        // and it writes back out (every value finite where the format needs it)
        (void)certipose::camera_task_to_json(in).dump();
    });
    return 0;
}
