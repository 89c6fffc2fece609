// Pi and the degree, once for the engine, its tools and its tests (C++17 has no std::numbers).
#pragma once

namespace mas {

inline constexpr double kPi = 3.14159265358979323846;
inline constexpr double kDegree = kPi / 180.0;  // one degree in radians

}  // namespace mas
