// expect: static assertion failed: certipose::pose_solver: Policies::schedule cannot drive Policies::orientation: hinted_schedule needs a certipose::BorrowingOrientationPolicy
// A user's orientation policy that models OrientationPolicy but not the hints the default
// schedule uses: the bundle is rejected where it is used, naming the concept it misses, instead
// of the solver quietly running one search per box (with_schedule<per_box_schedule> says so).
#include <certipose/cgal.hpp>

struct my_orientation {
    template <certipose::Interval I, certipose::CameraModel C>
    certipose::orientation_result<I> orient(const certipose::position_box<I>&, const certipose::facet&, const C&,
                                            double) const {
        return {};
    }
};
static_assert(certipose::OrientationPolicy<my_orientation, certipose::boost_interval, certipose::thin_lens_camera>);

int main() {
    const auto part = certipose::make_sample_part();
    const certipose::thin_lens_camera camera(certipose::thin_lens_parameters{
        .focal_length = 0.012, .f_stop = 8, .focus_distance = 0.6, .max_blur_circle = 6.9e-6,
        .pixel_pitch = 3.45e-6, .width_px = 2448, .height_px = 2048});
    const certipose::pose_solver<certipose::with_orientation<my_orientation>> solver(part.mesh, camera, {});
    return static_cast<int>(solver.solve(0).stats.valid);
}
