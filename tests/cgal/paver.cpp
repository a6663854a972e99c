// The typed paver and bisector tests of tests/core/paver.cpp, run over the CGAL interval
// backend (this executable links CGAL; the core one must not).
#include <certipose/interval/cgal_interval.hpp>

#define CERTIPOSE_PAVER_TEST_BACKENDS certipose::cgal_interval
#include "core/paver.cpp"
