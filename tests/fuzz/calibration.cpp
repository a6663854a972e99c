// libFuzzer harness of the calibration reader (io/calibration.hpp: OpenCV YAML/JSON, ROS
// camera_info YAML): parse_calibration returns a calibration whose values passed validation, or
// throws a certipose::error (never a yaml-cpp or nlohmann exception, never a crash).
#include "harness.hpp"

#include <certipose/io/calibration.hpp>

#include <cmath>
#include <cstdlib>

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    certipose_fuzz::accept_certipose_errors([&] {
        const certipose::calibration c = certipose::parse_calibration(certipose_fuzz::text(data, size), "fuzz.yaml");
        // What came back is what the validation promises.
        if (!(c.K(0, 0) > 0) || !(c.K(1, 1) > 0) || c.K(2, 2) != 1.0 || !(c.K(0, 2) > 0 && c.K(0, 2) < c.width_px) ||
            !(c.K(1, 2) > 0 && c.K(1, 2) < c.height_px))
            std::abort();
        for (double v : c.distortion.opencv())
            if (!std::isfinite(v)) std::abort();
    });
    return 0;
}
