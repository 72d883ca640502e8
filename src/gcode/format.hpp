#pragma once
// Numbers as text for reports and header lines: fixed decimals, so the
// output is the same on every machine.
#include <cstdio>
#include <string>

namespace scaffold::gcode {

inline std::string fixed(double v, int decimals) {
    char buf[64];
    std::snprintf(buf, sizeof buf, "%.*f", decimals, v);
    return buf;
}

}  // namespace scaffold::gcode
