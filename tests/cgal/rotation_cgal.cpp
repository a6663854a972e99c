// tests/core/rotation.cpp's typed test over the CGAL backend (the untyped ones run in core).
#include <certipose/interval/cgal_eigen.hpp>
#include <certipose/interval/cgal_interval.hpp>

#define CERTIPOSE_ROTATION_TEST_BACKENDS certipose::cgal_interval
#include "../core/rotation.cpp"
