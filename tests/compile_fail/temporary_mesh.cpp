// expect: use of deleted function .*pose_solver
// Issue: `pose_solver<> s(read_mesh(path), camera, task);` compiled and then read freed memory.
// The solver references the mesh; a temporary is refused (a deleted rvalue constructor).
#include <certipose/cgal.hpp>

int main() {
    const certipose::thin_lens_camera camera(certipose::thin_lens_parameters{
        .focal_length = 0.012, .f_stop = 8, .focus_distance = 0.6, .max_blur_circle = 6.9e-6,
        .pixel_pitch = 3.45e-6, .width_px = 2448, .height_px = 2048});
    certipose::pose_solver<> s(certipose::read_mesh("part.off"), camera, {.min_view_angle = 0.35});
    return static_cast<int>(s.solve(0).stats.valid);
}
