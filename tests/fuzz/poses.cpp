// libFuzzer harness of the POSES.json and PLAN.json readers (certipose-verify; io/plan_files.hpp):
// poses_from_json returns poses with finite, ordered bounds (a quaternion or matrix pose: a point
// position and a 2e-8 rad box around its converted angles, away from the gimbal lock), or throws a
// certipose::error; plan_from_json returns a plan that plan_to_json writes and plan_from_json reads
// back equal (no exception allowed there), or throws a certipose::error.
#include "harness.hpp"

#include <certipose/io/plan_files.hpp>

#include <cmath>
#include <cstdlib>
#include <optional>

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    certipose_fuzz::accept_certipose_errors([&] {
        const auto poses = certipose::poses_from_json(
            certipose::detail::json_io::parse(certipose_fuzz::text(data, size), "fuzz.json"));
        for (const auto& p : poses) {
            for (const auto* b : {&p.position, &p.orientation})
                for (const auto& c : *b)
                    if (!(c[0] <= c[1])) std::abort();  // the reader promised ordered bounds
            const bool converted = p.form == certipose::pose_form::quaternion || p.form == certipose::pose_form::matrix;
            certipose_fuzz::require(converted == p.converted.has_value());
            certipose_fuzz::require(p.pose.has_value() == (p.form == certipose::pose_form::exact));
            if (converted) {
                certipose_fuzz::require(std::sin((*p.converted)[4]) >= 0.5 * certipose::zxz_gimbal_limit);
                for (std::size_t k = 0; k < 3; ++k) {
                    certipose_fuzz::require(p.position[k][0] == p.position[k][1]);
                    const double width = p.orientation[k][1] - p.orientation[k][0];
                    certipose_fuzz::require(std::abs(width - 2 * certipose::converted_pose_half_width) < 1e-14);
                }
            }
        }
    });
    std::optional<certipose::plan_document> plan;
    certipose_fuzz::accept_certipose_errors([&] {
        plan = certipose::plan_from_json(certipose::detail::json_io::parse(certipose_fuzz::text(data, size), "PLAN.json"),
                                         "PLAN.json");
    });
    if (plan) {  // what was read is written and read back the same: no exception allowed here
        const auto text = certipose::json_text(certipose::plan_to_json(*plan));
        certipose_fuzz::require(certipose::plan_from_json(certipose::detail::json_io::parse(text, "again")) == *plan);
    }
    return 0;
}
