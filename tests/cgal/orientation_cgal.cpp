// tests/core/orientation.cpp's typed tests over the CGAL interval backend (the untyped ones
// run in core).
#include <certipose/interval/cgal_interval.hpp>

#define CERTIPOSE_ORIENTATION_TEST_BACKENDS certipose::cgal_interval
#define CERTIPOSE_ORIENTATION_TYPED_ONLY
#include "../core/orientation.cpp"
