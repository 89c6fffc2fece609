// Reading parts from files: STEP, IGES and BREP through OCCT's readers into a Shape, STL and OFF
// into a TriangleMesh; and the one closed triangle mesh the section kernel cuts for either kind.
#include <BRepBndLib.hxx>
#include <BRepBuilderAPI_Sewing.hxx>
#include <Bnd_Box.hxx>
#include <IFSelect_ReturnStatus.hxx>
#include <IGESControl_Reader.hxx>
#include <Message_ProgressRange.hxx>
#include <RWStl_Reader.hxx>
#include <STEPControl_Reader.hxx>
#include <Standard_ReadLineBuffer.hxx>
#include <TopExp.hxx>
#include <TopTools_IndexedMapOfShape.hxx>
#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <gp_XYZ.hxx>
#include <map>
#include <mutex>
#include <system_error>

#include "ShapeImpl.hpp"

namespace mas {

namespace {

namespace fs = std::filesystem;

std::string lowercase(std::string text) {
    std::transform(text.begin(), text.end(), text.begin(),
                   [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
    return text;
}

std::string lower_extension(const std::string& path) {
    return lowercase(fs::path(path).extension().string());
}

int count_of(const TopoDS_Shape& s, TopAbs_ShapeEnum type) {
    TopTools_IndexedMapOfShape map;
    TopExp::MapShapes(s, type, map);
    return map.Extent();
}

// STEP and IGES share XSControl_Reader: read, translate every root, take them as one shape.
// OCCT's STEP and IGES parsers keep global state: two reads at once (scripts on several threads)
// garble each other ("unreadable" good files). One at a time.
std::mutex exchange_mutex;

template <class Reader>
TopoDS_Shape read_exchange(const std::string& path, const char* format) {
    const std::lock_guard<std::mutex> one_at_a_time(exchange_mutex);
    Reader reader;
    if (occ::catching_signals([&] { return reader.ReadFile(path.c_str()); }) != IFSelect_RetDone)
        throw Error(ErrorCode::ReadFailed, path + ": unreadable or truncated " + format + " file");
    // A damaged file (an entity referring to one that is missing) crashes the translator: caught.
    TopoDS_Shape shape = occ::catching_signals([&] {
        reader.TransferRoots();
        return reader.OneShape();
    });
    if (shape.IsNull())
        throw Error(ErrorCode::EmptyInput, path + ": the " + format +
                                               " file holds no shape OCCT can translate (none, "
                                               "or only damaged entities)");
    return shape;
}

// OCCT's IGES reader accepts a truncated file and its translator then dereferences the entities
// that are missing (a segmentation fault on a B-rep IGES cut in its parameter section). IGES
// states its own length: the last line, the Terminate section, counts the lines of the Start,
// Global, Directory and Parameter sections. Check those counts before OCCT sees the file.
void require_complete_iges(const std::string& path) {
    std::ifstream in(path, std::ios::binary);
    if (!in) throw Error(ErrorCode::ReadFailed, path + ": cannot open the file");
    std::map<char, long> lines;  // per section letter (column 73 of the 80-column records)
    std::string terminate;
    for (std::string line; std::getline(in, line);) {
        if (!line.empty() && line.back() == '\r') line.pop_back();
        if (line.size() < 73) continue;
        ++lines[line[72]];
        if (line[72] == 'T') terminate = line;
    }
    if (terminate.empty())
        throw Error(ErrorCode::ReadFailed,
                    path + ": truncated or not an IGES file (no Terminate section)");
    for (std::size_t field = 0; field < 4; ++field) {
        const char section = terminate[8 * field];
        long expected = -1;
        try {
            expected = std::stol(terminate.substr(8 * field + 1, 7));
        } catch (const std::exception&) {
        }
        if (std::string("SGDP").find(section) == std::string::npos || expected < 0)
            throw Error(ErrorCode::ReadFailed, path + ": malformed IGES Terminate section");
        if (lines[section] != expected)
            throw Error(ErrorCode::ReadFailed, path + ": truncated IGES file (" +
                                                   std::to_string(lines[section]) +
                                                   " lines in section " + section + ", " +
                                                   std::to_string(expected) + " announced)");
    }
}

// IGES usually carries a solid as loose trimmed surfaces (OCCT's own writer does so by default):
// sew them into shells so that a closed part reaches single_solid() as one closed shell. The
// tolerance, 1e-5 of the part's size, closes the gaps an exporter's rounding leaves and nothing
// wider.
TopoDS_Shape sew_faces(const TopoDS_Shape& shape) {
    if (count_of(shape, TopAbs_SOLID) > 0 || count_of(shape, TopAbs_FACE) < 2) return shape;
    Bnd_Box box;
    BRepBndLib::Add(shape, box, Standard_False);
    const double diagonal = box.IsVoid() ? 0.0 : std::sqrt(box.SquareExtent());
    BRepBuilderAPI_Sewing sewing(std::max(1e-6, 1e-5 * diagonal));
    sewing.Add(shape);
    sewing.Perform();
    const TopoDS_Shape sewn = sewing.SewedShape();
    return sewn.IsNull() ? shape : sewn;
}

TopoDS_Shape read_brep_file(const std::string& path) {
    std::ifstream in(path, std::ios::binary);
    if (!in) throw Error(ErrorCode::ReadFailed, path + ": cannot open the file");
    return occ::read_brep(in, path);
}

// RWStl reads as many facets as a truncated STL holds and reports success; the cut then shows up
// later, as a mesh with holes. Say "truncated" instead: a binary STL is exactly 84 bytes plus 50
// per facet announced in its header, an ASCII one starts with "solid" and ends with "endsolid".
// That also tells the two apart: RWStl's own guess reads a file whose first 134 bytes are all
// ASCII as text (a binary STL of a simple part with zero facet normals: 0x00 and small coordinates
// such as 10.0f = 00 00 20 41), and one with a byte past '~' there as binary (an ASCII STL whose
// solid is named in UTF-8, "solid Bügel"), and then fails on either.
enum class StlKind { Binary, Ascii, AsciiNamingNanOrInf };

StlKind stl_kind(const std::string& path) {
    std::ifstream in(path, std::ios::binary);
    if (!in) throw Error(ErrorCode::ReadFailed, path + ": cannot open the file");
    const std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    if (bytes.size() >= 84) {
        const auto* p = reinterpret_cast<const unsigned char*>(bytes.data()) + 80;
        const std::uint64_t facets =
            p[0] | (p[1] << 8) | (p[2] << 16) | (std::uint64_t(p[3]) << 24);
        // (An ASCII file matches only if its bytes 80 to 83, text, count half a billion facets
        // and it is 25 GB long.)
        if (bytes.size() == 84 + 50 * facets) return StlKind::Binary;
    }
    // Keywords are read whatever their case, as RWStl's ASCII parser reads them: some exporters
    // write "SOLID ... FACET NORMAL ... ENDSOLID".
    const auto holds = [](const std::string& text, const std::string& word) {
        return std::search(text.begin(), text.end(), word.begin(), word.end(), [](char a, char b) {
                   return std::tolower(static_cast<unsigned char>(a)) == b;
               }) != text.end();
    };
    const auto first = bytes.find_first_not_of(" \t\r\n");
    if (first != std::string::npos && lowercase(bytes.substr(first, 5)) == "solid") {
        const auto last = bytes.find_last_not_of(" \t\r\n");
        const auto line = bytes.rfind('\n', last);
        const std::string tail = bytes.substr(line == std::string::npos ? 0 : line + 1);
        if (!holds(tail, "endsolid"))
            throw Error(ErrorCode::ReadFailed, path + ": truncated ASCII STL file (no 'endsolid')");
        return holds(bytes, "nan") || holds(bytes, "inf") ? StlKind::AsciiNamingNanOrInf
                                                          : StlKind::Ascii;
    }
    throw Error(ErrorCode::ReadFailed,
                path + ": truncated or not an STL file (its size does not match its facet count)");
}

// RWStl's ASCII parser gives up on a "nan" or "inf" coordinate in some positions, and in others
// drops the facet (the mesh then has holes): look for one first, so the message names the real
// problem.
bool ascii_stl_has_non_finite(const std::string& path) {
    std::ifstream in(path);
    for (std::string word; in >> word;) {
        if (lowercase(word) != "vertex") continue;
        for (int k = 0; k < 3; ++k) {
            std::string number;
            if (!(in >> number)) return false;
            char* end = nullptr;
            const double v = std::strtod(number.c_str(), &end);
            if (end != number.c_str() && !std::isfinite(v)) return true;
        }
    }
    return false;
}

// RWStl_Reader's parsers, told the format: they merge nodes of equal coordinates (so the mesh
// comes out welded) and drop facets with two corners at one node.
class StlMeshReader final : public RWStl_Reader {
public:
    explicit StlMeshReader(TriangleMesh& mesh) : mesh_(mesh) {}
    Standard_Integer AddNode(const gp_XYZ& p) override {
        mesh_.vertices.emplace_back(p.X(), p.Y(), p.Z());
        return static_cast<Standard_Integer>(mesh_.vertices.size() - 1);
    }
    void AddTriangle(Standard_Integer a, Standard_Integer b, Standard_Integer c) override {
        mesh_.triangles.emplace_back(a, b, c);
    }

private:
    TriangleMesh& mesh_;
};

TriangleMesh read_stl(const std::string& path) {
    const StlKind kind = stl_kind(path);
    if (kind == StlKind::AsciiNamingNanOrInf && ascii_stl_has_non_finite(path))
        throw Error(ErrorCode::NonFiniteCoordinate,
                    path + ": a vertex has NaN or infinite coordinates");
    TriangleMesh mesh;
    std::ifstream in(path, std::ios::binary);
    if (!in) throw Error(ErrorCode::ReadFailed, path + ": cannot open the file");
    const Handle(StlMeshReader) reader = new StlMeshReader(mesh);
    bool read = true;
    if (kind == StlKind::Binary) {
        read = reader->ReadBinary(in, Message_ProgressRange());
    } else {
        // One solid after another ("solid ... endsolid"), as RWStl_Reader::Read takes them.
        in.seekg(0, std::ios::end);
        const std::streampos end = in.tellg();
        in.seekg(0, std::ios::beg);
        Standard_ReadLineBuffer buffer(1024);
        while (read && in.good()) {
            read = reader->ReadAscii(in, buffer, end, Message_ProgressRange());
            in >> std::ws;
        }
        read = read && !in.bad();
    }
    if (!read) throw Error(ErrorCode::ReadFailed, path + ": unreadable or truncated STL file");
    for (const Eigen::Vector3d& v : mesh.vertices)
        if (!v.allFinite())
            throw Error(ErrorCode::NonFiniteCoordinate,
                        path + ": a vertex has NaN or infinite coordinates");
    if (mesh.triangles.empty()) throw Error(ErrorCode::EmptyInput, path + ": no triangles");
    return mesh;
}

}  // namespace

Model read_model(const std::string& path) {
    std::error_code ec;
    if (path.empty()) throw Error(ErrorCode::ReadFailed, "no file name given (an empty path)");
    if (!fs::exists(path, ec)) throw Error(ErrorCode::ReadFailed, path + ": no such file");
    if (!fs::is_regular_file(path, ec)) throw Error(ErrorCode::ReadFailed, path + ": not a file");
    if (fs::file_size(path, ec) == 0 && !ec)
        throw Error(ErrorCode::EmptyInput, path + ": the file is empty");

    const std::string ext = lower_extension(path);
    Model model;
    model.name = fs::path(path).filename().string();
    try {
        if (ext == ".step" || ext == ".stp") {
            model.shape = occ::wrap(read_exchange<STEPControl_Reader>(path, "STEP"));
        } else if (ext == ".iges" || ext == ".igs") {
            require_complete_iges(path);
            model.shape = occ::wrap(sew_faces(read_exchange<IGESControl_Reader>(path, "IGES")));
        } else if (ext == ".brep" || ext == ".brp") {
            model.shape = occ::wrap(read_brep_file(path));
        } else if (ext == ".stl") {
            model.kind = Model::Kind::Mesh;
            model.mesh = read_stl(path);
        } else if (ext == ".off") {
            model.kind = Model::Kind::Mesh;
            model.mesh = read_off(path);
        } else {
            throw Error(ErrorCode::UnsupportedFormat,
                        path + ": unsupported file type '" + ext +
                            "' (expected .step, .stp, .iges, .igs, .brep, .brp, .stl or .off)");
        }
    } catch (const Standard_Failure& e) {
        throw Error(ErrorCode::ReadFailed, occ::failure_message(path, e));
    }
    return model;
}

TriangleMesh model_mesh(const Model& model, const TessellationParams& params) {
    const std::string what = model.name.empty() ? std::string("model") : model.name;
    if (model.kind == Model::Kind::Solid) return occ::tessellate(model.shape, params, what);
    TriangleMesh mesh = model.mesh;
    require_closed_mesh(mesh, what);
    require_one_solid(mesh, what);
    canonical_order(mesh);
    return mesh;
}

}  // namespace mas
