// The second translation unit of certipose::precompiled: the pipelines of
// certipose/detail/precompiled.hpp — the default one, and calibrated_camera's (any camera
// model, e.g. one read from JSON) under each occlusion policy, what the programs
// (certipose-solve, certipose-part) offer with --occlusion aabb|boolean|none. The definitions
// they call and the boolean policy are in certipose_precompiled.cpp.
#include <certipose/cgal.hpp>

template class certipose::pose_solver<certipose::default_policies>;
template class certipose::pose_solver<certipose::with_camera<certipose::calibrated_camera>>;
template class certipose::pose_solver<
    certipose::with_occlusion<certipose::basic_boolean_occlusion<void>, certipose::with_camera<certipose::calibrated_camera>>>;
template class certipose::pose_solver<
    certipose::with_occlusion<certipose::no_occlusion, certipose::with_camera<certipose::calibrated_camera>>>;
