// certipose/detail/format.hpp — the one way certipose writes a double as text.
//
// Error messages name the offending value, and mesh/PLY/JSON writers must read back the same
// double, so both use the shortest text that round-trips (std::to_chars): "0.05", "1e-09",
// "-inf", "nan". std::to_string would print 1e-09 as "0.000000", hiding the value the message
// is about; an ostream needs a precision and a locale.
#pragma once

#include <charconv>
#include <string>
#include <system_error>

namespace certipose::detail {

/// Appends the shortest round-trip text of v to out.
inline void append_double(std::string& out, double v) {
    char buf[32];  // the longest shortest form, "-2.2250738585072014e-308", has 24 characters
    const auto r = std::to_chars(buf, buf + sizeof buf, v);
    if (r.ec == std::errc{}) out.append(buf, r.ptr);
    else out += '?';
}

/// The shortest round-trip text of v.
inline std::string format_double(double v) {
    std::string s;
    append_double(s, v);
    return s;
}

}  // namespace certipose::detail
