// A downstream program of certipose::step from the installed package: <certipose/io/read_step.hpp>
// with OpenCASCADE found again by certiposeConfig.cmake (tests/consumer/installed/CMakeLists.txt).
#include <certipose/io/read_step.hpp>

#include <cstdio>

int main() {
    bool refused = false;
    try {
        (void)certipose::read_step("no-such-part.step");
    } catch (const certipose::io_error& e) {
        refused = e.path() == "no-such-part.step";
    }
    const bool ok = refused && certipose::is_step_path("PART.STP") && !certipose::is_step_path("part.off");
    std::printf("consumer (step): %s\n", ok ? "ok" : "FAILED");
    return ok ? 0 : 1;
}
