// Writing shapes to files: the sub-components of a decomposition go out as STEP.
#include <IFSelect_ReturnStatus.hxx>
#include <Interface_Static.hxx>
#include <STEPControl_Writer.hxx>

#include "ShapeImpl.hpp"

namespace mas {

void write_step(const Shape& shape, const std::string& path) {
    if (shape.is_null()) throw Error(ErrorCode::EmptyInput, path + ": nothing to write");
    try {
        STEPControl_Writer writer;
        Interface_Static::SetCVal("write.step.unit", "MM");
        if (writer.Transfer(occ::occt(shape), STEPControl_AsIs) != IFSelect_RetDone)
            throw Error(ErrorCode::GeometryFailure, path + ": the shape cannot be written as STEP");
        if (writer.Write(path.c_str()) != IFSelect_RetDone)
            throw Error(ErrorCode::WriteFailed, path + ": cannot write the file");
    } catch (const Standard_Failure& failure) {
        throw Error(ErrorCode::GeometryFailure, occ::failure_message(path, failure));
    }
}

}  // namespace mas
