#include "mas/Error.hpp"

#include <sstream>

namespace mas {

const char* to_string(ErrorCode code) {
    switch (code) {
        case ErrorCode::InvalidArgument:
            return "invalid_argument";
        case ErrorCode::EmptyInput:
            return "empty_input";
        case ErrorCode::ReadFailed:
            return "read_failed";
        case ErrorCode::WriteFailed:
            return "write_failed";
        case ErrorCode::UnsupportedFormat:
            return "unsupported_format";
        case ErrorCode::NotASolid:
            return "not_a_solid";
        case ErrorCode::MultipleSolids:
            return "multiple_solids";
        case ErrorCode::OpenMesh:
            return "open_mesh";
        case ErrorCode::NonFiniteCoordinate:
            return "non_finite_coordinate";
        case ErrorCode::GeometryFailure:
            return "geometry_failure";
        case ErrorCode::UnreachableOrientation:
            return "unreachable_orientation";
        case ErrorCode::OutOfTravel:
            return "out_of_travel";
        case ErrorCode::Cancelled:
            return "cancelled";
    }
    return "unknown";
}

std::string format_number(double value, int digits) {
    std::ostringstream out;
    out.precision(digits);
    out << value;
    return out.str();
}

}  // namespace mas
