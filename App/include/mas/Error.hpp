// Engine errors: one typed status for every kind of bad input or failure, carried by one exception.
// Nothing else leaves the engine: OCCT's Standard_Failure and std exceptions are translated at its
// edge.
#pragma once

#include <stdexcept>
#include <string>

namespace mas {

enum class ErrorCode {
    InvalidArgument,         // a parameter out of its range (zero step, zero normal, NaN, ...)
    EmptyInput,              // an empty file, a shape or mesh with nothing in it
    ReadFailed,              // a file that does not exist, cannot be read or is truncated
    WriteFailed,             // an output file that cannot be written
    UnsupportedFormat,       // a file extension the engine does not read
    NotASolid,               // a face, a wire, an open shell where a closed solid is expected
    MultipleSolids,          // several solids where exactly one is expected
    OpenMesh,                // a triangle mesh with holes or non-manifold edges
    NonFiniteCoordinate,     // NaN, infinite or out-of-range (kMaxCoordinateMm) coordinates
    GeometryFailure,         // the geometry kernel failed on valid-looking input
    UnreachableOrientation,  // a tool axis the machine's rotary axes cannot turn to the nozzle
    OutOfTravel,             // a program taking the machine's X, Y or Z past its travel limits
    Cancelled,               // the caller cancelled a long computation
};

// Stable lower-case name of a code, e.g. "open_mesh"; used by the Python binding and the CLI.
const char* to_string(ErrorCode code);

// A number as messages show it: `digits` significant digits, exponent when needed ("0.25",
// "1e-07", "1e+300", "nan"). (std::to_string's fixed six decimals show 1e-7 as "0.000000".)
std::string format_number(double value, int digits = 6);

class Error : public std::runtime_error {
public:
    Error(ErrorCode code, const std::string& message) : std::runtime_error(message), code_(code) {}
    ErrorCode code() const { return code_; }

private:
    ErrorCode code_;
};

}  // namespace mas
