// mas::Shape over an OCCT TopoDS_Shape: BREP text in and out, what a shape is made of, and the
// "exactly one closed solid" check every later stage relies on.
#include <BRepAlgoAPI_Fuse.hxx>
#include <BRepBndLib.hxx>
#include <BRepBuilderAPI_Copy.hxx>
#include <BRepBuilderAPI_MakeSolid.hxx>
#include <BRepCheck_Analyzer.hxx>
#include <BRepGProp.hxx>
#include <BRepLib.hxx>
#include <BRepTools.hxx>
#include <BRep_Builder.hxx>
#include <BRep_Tool.hxx>
#include <Bnd_Box.hxx>
#include <GProp_GProps.hxx>
#include <OSD.hxx>
#include <ShapeUpgrade_UnifySameDomain.hxx>
#include <TopExp.hxx>
#include <TopExp_Explorer.hxx>
#include <TopTools_IndexedDataMapOfShapeListOfShape.hxx>
#include <TopTools_IndexedMapOfShape.hxx>
#include <TopTools_ListOfShape.hxx>
#include <TopoDS.hxx>
#include <TopoDS_Shell.hxx>
#include <TopoDS_Solid.hxx>
#include <algorithm>
#include <cfenv>
#include <iterator>
#include <mutex>
#include <sstream>
#include <vector>

#include "ShapeImpl.hpp"

namespace mas {

namespace occ {

double volume_of(const TopoDS_Shape& shape) {
    GProp_GProps props;
    BRepGProp::VolumeProperties(shape, props);
    return props.Mass();
}

std::vector<TopoDS_Shape> solids_of(const TopoDS_Shape& shape) {
    std::vector<TopoDS_Shape> out;
    for (TopExp_Explorer x(shape, TopAbs_SOLID); x.More(); x.Next()) out.push_back(x.Current());
    return out;
}

double precise_volume_of(const TopoDS_Shape& shape, double relative) {
    GProp_GProps props;
    BRepGProp::VolumeProperties(shape, props, relative);
    return props.Mass();
}

double max_tolerance(const TopoDS_Shape& shape) {
    return std::max(BRep_Tool::MaxTolerance(shape, TopAbs_VERTEX),
                    BRep_Tool::MaxTolerance(shape, TopAbs_EDGE));
}

bool widened(const TopoDS_Shape& unified, double before) {
    return max_tolerance(unified) > std::max(kUnifiedToleranceMm, 10.0 * before);
}

TopoDS_Shape unify_in_place(const TopoDS_Shape& shape) {
    ShapeUpgrade_UnifySameDomain u(shape, Standard_True, Standard_True, Standard_False);
    u.Build();
    return u.Shape();
}

TopoDS_Shape unify(const TopoDS_Shape& shape) {
    try {
        const TopoDS_Shape out = unify_in_place(BRepBuilderAPI_Copy(shape).Shape());
        return widened(out, max_tolerance(shape)) ? shape : out;
    } catch (const Standard_Failure&) {
        return shape;  // a piece of an eye bolt's ring: "TopoDS_Vertex hasn't gp_Pnt"
    }
}

Eigen::AlignedBox3d tight_bounds(const TopoDS_Shape& shape) {
    Bnd_Box box;
    BRepBndLib::AddOptimal(shape, box, Standard_False, Standard_False);
    Eigen::AlignedBox3d bounds;
    if (box.IsVoid()) return bounds;
    double x0, y0, z0, x1, y1, z1;
    box.Get(x0, y0, z0, x1, y1, z1);
    return Eigen::AlignedBox3d(Eigen::Vector3d(x0, y0, z0), Eigen::Vector3d(x1, y1, z1));
}

Shape wrap(const TopoDS_Shape& shape) {
    auto impl = std::make_shared<Shape::Impl>();
    impl->shape = shape;
    return Shape(std::move(impl));
}

namespace {

// The process's handlers while OCCT's are in, and how many SignalHandlers hold them in;
// OCCT's handlers, once OSD::SetSignal has shown them.
std::mutex signal_mutex;
int signal_holders = 0;
std::vector<struct sigaction> process_handlers(NSIG);
std::vector<struct sigaction> occt_handlers(NSIG);
bool occt_handlers_known = false;
constexpr int kFatalSignals[] = {SIGSEGV, SIGBUS, SIGFPE, SIGILL};

bool fatal(int sig) {
    return std::find(std::begin(kFatalSignals), std::end(kFatalSignals), sig) !=
           std::end(kFatalSignals);
}

}  // namespace

SignalHandlers::SignalHandlers() {
    traps_ = fegetexcept();
    const std::lock_guard<std::mutex> lock(signal_mutex);
    if (signal_holders++ > 0) {
        fedisableexcept(FE_ALL_EXCEPT);  // what OSD::SetSignal does for the first one's thread
        return;
    }
    for (const int sig : kFatalSignals) sigaction(sig, nullptr, &process_handlers[sig]);
    if (occt_handlers_known) {
        // OCCT's, for the fatal signals alone: OSD::SetSignal would take SIGINT too, for as long
        // as it takes to put it back, each time (another thread reading SIGINT's handler then,
        // or a Ctrl-C, met OCCT's), and turns this thread's traps off, as here.
        for (const int sig : kFatalSignals) sigaction(sig, &occt_handlers[sig], nullptr);
        fedisableexcept(FE_ALL_EXCEPT);
        return;
    }
    // The first time: OSD::SetSignal, whose handlers for the fatal signals are kept. It takes
    // SIGINT, SIGHUP, SIGQUIT and more too: those go back at once, never to be taken again.
    std::vector<struct sigaction> before(NSIG);
    for (int sig = 1; sig < NSIG; ++sig) sigaction(sig, nullptr, &before[sig]);
    OSD::SetSignal(OSD_SignalMode_Set, Standard_False);
    for (const int sig : kFatalSignals) sigaction(sig, nullptr, &occt_handlers[sig]);
    occt_handlers_known = true;
    for (int sig = 1; sig < NSIG; ++sig)
        if (!fatal(sig) && sig != SIGKILL && sig != SIGSTOP) sigaction(sig, &before[sig], nullptr);
}

SignalHandlers::~SignalHandlers() {
    {
        const std::lock_guard<std::mutex> lock(signal_mutex);
        if (--signal_holders == 0)
            for (const int sig : kFatalSignals) sigaction(sig, &process_handlers[sig], nullptr);
    }
    fedisableexcept(FE_ALL_EXCEPT);
    if (traps_ > 0) feenableexcept(traps_);
}

std::string failure_message(const std::string& what, const Standard_Failure& failure) {
    const char* text = failure.GetMessageString();
    std::string message = text != nullptr ? text : "";
    if (message.empty()) message = failure.DynamicType()->Name();
    return what + ": OCCT failed (" + message + ")";
}

TopoDS_Shape read_brep(std::istream& in, const std::string& what) {
    // BRepTools::Read does not report garbage: it looks for its header line and silently returns a
    // null shape when there is none, which is also what a file holding a null shape gives. Look
    // for the header ourselves so that the two cases get their own errors.
    std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    if (text.find_first_not_of(" \t\r\n") == std::string::npos)
        throw Error(ErrorCode::EmptyInput, what + ": the BREP data is empty");
    if (text.find("CASCADE Topology V") == std::string::npos)
        throw Error(ErrorCode::ReadFailed,
                    what + ": not OCCT BREP data (no 'CASCADE Topology' header)");
    TopoDS_Shape shape;
    try {
        // OCCT's BREP reader hardly checks its stream. On truncated text some of its loops spin
        // forever at the failed stream (a text cut inside "TShapes"), and its number reader
        // returns 0 at the end of the stream, so a cut inside a curve builds a null curve that
        // crashes the next constructor (a text cut inside a trimmed curve's basis line). Make
        // reaching the end throw: complete data never reads past its last token, given the
        // newline added here.
        text.push_back('\n');
        std::istringstream stream(text);
        stream.exceptions(std::ios::failbit | std::ios::badbit | std::ios::eofbit);
        BRep_Builder builder;
        occ::catching_signals([&] { BRepTools::Read(shape, stream, builder); });
    } catch (const std::ios_base::failure&) {
        throw Error(ErrorCode::ReadFailed, what + ": truncated or malformed BREP data");
    } catch (const Standard_Failure& e) {
        throw Error(ErrorCode::ReadFailed,
                    occ::failure_message(what, e) + ": truncated or malformed BREP data");
    }
    if (shape.IsNull()) {
        // A null shape is written as complete tables ending in the null marker "*". The reader
        // also returns a null shape, without a word, when a table header is cut short.
        const auto last = text.find_last_not_of(" \t\r\n");
        if (last == std::string::npos || text[last] != '*')
            throw Error(ErrorCode::ReadFailed, what + ": truncated or malformed BREP data");
        throw Error(ErrorCode::EmptyInput, what + ": the BREP data holds no shape");
    }
    return shape;
}

}  // namespace occ

namespace {

const std::shared_ptr<const Shape::Impl>& null_impl() {
    static const auto impl = std::make_shared<const Shape::Impl>();
    return impl;
}

std::string counted(int n, const char* singular, const char* plural) {
    return std::to_string(n) + " " + (n == 1 ? singular : plural);
}

int extent(const TopoDS_Shape& s, TopAbs_ShapeEnum type) {
    TopTools_IndexedMapOfShape map;
    TopExp::MapShapes(s, type, map);
    return map.Extent();
}

// Sub-shapes of `type` that no `parent` contains (faces outside solids, edges outside faces).
int free_count(const TopoDS_Shape& s, TopAbs_ShapeEnum type, TopAbs_ShapeEnum parent) {
    TopTools_IndexedDataMapOfShapeListOfShape ancestors;
    TopExp::MapShapesAndAncestors(s, type, parent, ancestors);
    int n = 0;
    for (int i = 1; i <= ancestors.Extent(); ++i)
        if (ancestors(i).IsEmpty()) ++n;
    return n;
}

// Why a shell is open: its edges used by one face only (holes) and by more than two faces
// (non-manifold). Degenerated edges, such as a sphere's poles, do not count; a seam (the closing
// edge of a cylinder) appears twice in its one face, so it counts as closed.
std::string open_shell_message(const std::string& what, const TopoDS_Shape& shell) {
    TopTools_IndexedMapOfShape edges;
    std::vector<int> uses;
    for (TopExp_Explorer x(shell, TopAbs_EDGE); x.More(); x.Next()) {
        if (BRep_Tool::Degenerated(TopoDS::Edge(x.Current()))) continue;
        const int i = edges.Add(x.Current());
        if (i > static_cast<int>(uses.size())) uses.resize(i, 0);
        ++uses[i - 1];
    }
    const auto boundary = std::count(uses.begin(), uses.end(), 1);
    const auto non_manifold = std::count_if(uses.begin(), uses.end(), [](int n) { return n > 2; });
    std::string why = counted(int(boundary), "boundary edge", "boundary edges");
    if (non_manifold > 0)
        why += ", " + counted(int(non_manifold), "non-manifold edge", "non-manifold edges");
    return what + ": an open shell, not a closed solid (" + why + ")";
}

// Several solids that share material (a CompSolid, as Part's BooleanFragments makes; a compound of
// a plate and a post standing on it or sunk into it) are one body to deposit: their union, its
// coplanar faces merged so that it reads as if modelled in one piece. Solids apart, or meeting only
// along an edge or at a point, stay several bodies: which part was meant cannot be guessed.
TopoDS_Solid fused_solids(const std::string& what, const TopTools_IndexedMapOfShape& solids) {
    const std::string several =
        what + ": " + std::to_string(solids.Extent()) + " solids where one is expected";
    TopTools_ListOfShape arguments, tools;
    arguments.Append(solids(1));
    for (int i = 2; i <= solids.Extent(); ++i) tools.Append(solids(i));
    BRepAlgoAPI_Fuse fuse;
    fuse.SetArguments(arguments);
    fuse.SetTools(tools);
    fuse.SetRunParallel(Standard_False);
    occ::catching_signals([&] { fuse.Build(); });
    if (!fuse.IsDone() || fuse.HasErrors())
        throw Error(ErrorCode::GeometryFailure,
                    several +
                        ", and OCCT's Boolean fuse fails on them (fuse them in FreeCAD "
                        "and give the result)");
    const TopoDS_Shape united = occ::unify(fuse.Shape());
    TopTools_IndexedMapOfShape bodies;
    TopExp::MapShapes(united, TopAbs_SOLID, bodies);
    if (bodies.Extent() != 1)
        throw Error(ErrorCode::MultipleSolids,
                    several + "; solids that share material are fused into one, and these make " +
                        std::to_string(bodies.Extent()) +
                        " bodies apart (or meeting only along an edge or at a point): give each "
                        "on its own");
    return TopoDS::Solid(bodies(1));
}

}  // namespace

Shape::Shape() : impl_(null_impl()) {}
Shape::~Shape() = default;
Shape::Shape(const Shape&) = default;
Shape& Shape::operator=(const Shape&) = default;
Shape::Shape(std::shared_ptr<const Impl> impl) : impl_(impl ? std::move(impl) : null_impl()) {}

Shape Shape::from_brep_string(const std::string& brep) {
    std::istringstream in(brep);
    return occ::wrap(occ::read_brep(in, "BREP text"));
}

std::string Shape::to_brep_string() const {
    try {
        std::ostringstream out;
        // Without triangulations: a Shape never carries one (tessellate() meshes a copy), and a
        // mesh read with the shape would only grow the text.
        BRepTools::Write(impl_->shape, out, Standard_False, Standard_False,
                         TopTools_FormatVersion_CURRENT);
        return out.str();
    } catch (const Standard_Failure& e) {
        throw Error(ErrorCode::GeometryFailure, occ::failure_message("BREP export", e));
    }
}

bool Shape::is_null() const { return impl_->shape.IsNull(); }

ShapeInfo Shape::info() const {
    ShapeInfo info;
    const TopoDS_Shape& s = impl_->shape;
    if (s.IsNull()) return info;
    try {
        info.solids = extent(s, TopAbs_SOLID);
        info.shells = extent(s, TopAbs_SHELL);
        info.faces = extent(s, TopAbs_FACE);
        info.edges = extent(s, TopAbs_EDGE);
        info.free_faces = free_count(s, TopAbs_FACE, TopAbs_SOLID);
        info.free_edges = free_count(s, TopAbs_EDGE, TopAbs_FACE);
        for (TopExp_Explorer x(s, TopAbs_SOLID); x.More(); x.Next()) {
            GProp_GProps props;
            BRepGProp::VolumeProperties(x.Current(), props);
            info.volume_mm3 += props.Mass();
        }
        info.bounds = occ::tight_bounds(s);
    } catch (const Standard_Failure& e) {
        throw Error(ErrorCode::GeometryFailure, occ::failure_message("shape info", e));
    }
    return info;
}

Shape Shape::single_solid(const std::string& what) const {
    const TopoDS_Shape& s = impl_->shape;
    if (s.IsNull()) throw Error(ErrorCode::EmptyInput, what + ": the shape is empty");
    try {
        TopTools_IndexedMapOfShape solids, shells;
        TopExp::MapShapes(s, TopAbs_SOLID, solids);
        TopExp::MapShapes(s, TopAbs_SHELL, shells);
        const int faces = extent(s, TopAbs_FACE);
        TopoDS_Solid solid;
        if (solids.Extent() >= 1) {
            for (int i = 1; i <= solids.Extent(); ++i)
                for (TopExp_Explorer x(solids(i), TopAbs_SHELL); x.More(); x.Next())
                    if (!BRep_Tool::IsClosed(x.Current()))
                        throw Error(ErrorCode::NotASolid, open_shell_message(what, x.Current()));
            // A face beside the solid may be material the part is meant to have (a wall left as
            // a surface, a lid not yet fused): building the solid without it would be a guess.
            // Loose edges and vertices (axes, sketches) hold no material and are left out.
            const int loose = free_count(s, TopAbs_FACE, TopAbs_SOLID);
            if (loose > 0) {
                const bool one = solids.Extent() == 1;
                throw Error(
                    ErrorCode::NotASolid,
                    what + ": " +
                        (one ? std::string("one solid") : counted(solids.Extent(), "", "solids")) +
                        " and " + counted(loose, "face", "faces") +
                        (one ? " outside it; give the solid alone, or fuse the faces' "
                               "material into it"
                             : " outside them; give the solids alone, or fuse the faces' "
                               "material into them"));
            }
            solid = solids.Extent() == 1 ? TopoDS::Solid(solids(1)) : fused_solids(what, solids);
        } else if (faces == 0) {
            if (extent(s, TopAbs_EDGE) == 0 && extent(s, TopAbs_VERTEX) == 0)
                throw Error(ErrorCode::EmptyInput, what + ": the shape has nothing in it");
            throw Error(ErrorCode::NotASolid, what + ": not a solid (0 faces, 0 solids; " +
                                                  counted(extent(s, TopAbs_EDGE), "edge", "edges") +
                                                  ")");
        } else if (shells.Extent() == 1 && extent(shells(1), TopAbs_FACE) == faces) {
            // A lone shell, as some exporters write a solid: accepted when it is closed, wrapped
            // into the solid it bounds and oriented so that its volume is positive.
            const TopoDS_Shell& shell = TopoDS::Shell(shells(1));
            if (!BRep_Tool::IsClosed(shell))
                throw Error(ErrorCode::NotASolid, open_shell_message(what, shell));
            BRepBuilderAPI_MakeSolid make(shell);
            if (!make.IsDone())
                throw Error(ErrorCode::NotASolid,
                            what + ": a closed shell that does not bound a solid");
            solid = make.Solid();
            BRepLib::OrientClosedSolid(solid);
        } else {
            std::string in_shells;
            if (shells.Extent() > 0)
                in_shells = " in " + counted(shells.Extent(), "shell", "shells");
            throw Error(ErrorCode::NotASolid, what + ": not a solid (" +
                                                  counted(faces, "face", "faces") + in_shells +
                                                  ", 0 solids)");
        }

        if (!occ::catching_signals([&] { return BRepCheck_Analyzer(solid).IsValid(); }))
            throw Error(ErrorCode::NotASolid,
                        what +
                            ": an invalid solid (OCCT's shape check finds faults in its faces, "
                            "edges or tolerances)");
        // An inside-out solid (negative volume) is turned right side out here, once, so that
        // the mesh, the exact section's inside test and the volume all agree.
        GProp_GProps props;
        BRepGProp::VolumeProperties(solid, props);
        if (props.Mass() < 0.0) solid.Reverse();
        if (s.IsSame(solid) && s.Orientation() == solid.Orientation()) return *this;
        return occ::wrap(solid);
    } catch (const Standard_Failure& e) {
        throw Error(ErrorCode::GeometryFailure, occ::failure_message(what, e));
    }
}

}  // namespace mas
