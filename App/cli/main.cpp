// multiaxis-slicer: the engine on STEP / IGES / BREP / STL / OFF files, outside FreeCAD.
// Sub-commands grow with the pipeline: `sections` (cross-section areas and centroids), `axis` (the
// centroidal axis), `decompose` (the tree of sub-components), `slice` (layers and paths).
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <functional>
#include <iomanip>
#include <iostream>
#include <map>
#include <memory>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include "mas/Angles.hpp"
#include "mas/CentroidalAxis.hpp"
#include "mas/Decompose.hpp"
#include "mas/Error.hpp"
#include "mas/Gcode.hpp"
#include "mas/Polygon2.hpp"
#include "mas/Progress.hpp"
#include "mas/Section.hpp"
#include "mas/Shape.hpp"
#include "mas/SlicePart.hpp"

namespace {

const char* kUsage =
    "usage: multiaxis-slicer sections FILE [--normal X,Y,Z] [--step MM] [--deflection MM]\n"
    "                                      [--json [OUT.json]]\n"
    "       multiaxis-slicer axis FILE [--step MM] [--distance-threshold MM] [--eps MM]\n"
    "                                  [--break-angle DEG] [--base-z MM] [--frame DEG]\n"
    "                                  [--deflection MM] [--json [OUT.json]]\n"
    "       multiaxis-slicer decompose FILE [axis options] [--face-angle DEG]\n"
    "                                       [--concave-angle DEG] [--no-fallback]\n"
    "                                       [--min-height MM] [--max-tilt DEG]\n"
    "                                       [--keep-branches B[,B...]]\n"
    "                                       [--square-branches B[,B...]] [--step-dir DIR]\n"
    "                                       [--stl-dir DIR] [--progress]\n"
    "                                       [--json [OUT.json]]\n"
    "       multiaxis-slicer slice FILE [axis options] [--min-layer MM] [--max-layer MM]\n"
    "                                   [--max-volume-difference F] [--eps-angle DEG]\n"
    "                                   [--overhang-angle DEG] [--max-tilt DEG]\n"
    "                                   [--volume-samples N] [--strict]\n"
    "                                   [--bead-width MM] [--overlap F] [--contours N]\n"
    "                                   [--infill raster|contour|none] [--raster-angle DEG]\n"
    "                                   [--raster-angle-step DEG] [--min-feature MM]\n"
    "                                   [--measure-coverage] [--fill-holes MM] [--one-component]\n"
    "                                   [--allow-collisions] [--progress]\n"
    "                                   [nozzle options] [--no-plate-check]\n"
    "                                   [--gcode OUT.ngc [machine options]] [--json [OUT.json]]\n"
    "       multiaxis-slicer --help | --version\n"
    "\n"
    "sections   cut the part with parallel planes STEP mm apart along NORMAL (default 0,0,1 and\n"
    "           1 mm), each in the middle of its slab, and print every section's area (mm^2),\n"
    "           region count and centroid.\n"
    "axis       the part's centroidal axis (Ruan et al. Sec. 3): nodes, links and branches.\n"
    "           --step and --distance-threshold default to values derived from the part (0),\n"
    "           --eps to 0.001 mm, --break-angle to 30 degrees, --base-z to the part's lowest z,\n"
    "           --frame (the turn about Z of the +-X and +-Y it marches along, degrees) to the\n"
    "           one lining them up with the part's sides, 0 when they do not agree on one.\n"
    "decompose  split the part into sub-components at its axis' turns and branches (Sec. 4.1):\n"
    "           the tree, each component's build direction, base face and volume; --step-dir\n"
    "           writes every component as DIR/component_NNN.step. A mesh is split at section\n"
    "           planes only (the pieces slice starts from): --stl-dir writes them as\n"
    "           DIR/component_NNN.stl; the face options do not apply. A child\n"
    "           reaches at least --min-height (default 0) and one axis step past its cut, and\n"
    "           is built no more than --max-tilt (default 100) degrees from +Z, the machine's\n"
    "           reach: nothing is built straight down. --keep-branches leaves those axis\n"
    "           branches in their fathers (slice keeps so those the nozzle cannot reach).\n"
    "           A branch running between the six directions is cut square to its own line\n"
    "           (\"turned\": true); --square-branches cuts those square to their directions\n"
    "           (slice does so where the turned cuts leave the nozzle no way).\n"
    "slice      adaptive multi-axis layers of every sub-component (Sec. 4.2) and the bead paths\n"
    "           in every layer: per layer its plane, thickness range, volumetric difference and\n"
    "           unsupported area; --json adds its regions, its unsupported regions (on the\n"
    "           plane below it) and its paths (points, tool axis, thickness).\n"
    "           Defaults: layers 0.5 to 2 mm, volume difference 0.1, bead 1 mm, overlap 0.15,\n"
    "           2 contours, raster infill, --max-tilt 100: no layer or component tilts further\n"
    "           from +Z (the machine's reach; with --gcode and --a-limits, the farther A limit,\n"
    "           within 90 to 180). A solid is decomposed with --min-height at --min-layer;\n"
    "           a mesh is split at section planes where its axis turns or branches, or sliced\n"
    "           as one component with --one-component. A branch whose own component's layers\n"
    "           would meet the plate or what is deposited before them (nozzle options below)\n"
    "           stays in its father, and a part whose layers still would is sliced as one\n"
    "           component if that leaves fewer; --allow-collisions keeps the first split and\n"
    "           lists such layers. --fill-holes MM deposits a solid's round holes up to MM\n"
    "           across solid where their axis leans past the overhang angle off the build\n"
    "           direction (their ceilings would overhang), listing them to drill afterwards\n"
    "           (default 0: none).\n"
    "           The layers are sequenced so that the nozzle keeps clear of what is deposited\n"
    "           (Eq. 10), brothers built together where one would block the other; layers the\n"
    "           order found leaves in the way are listed. Nozzle options (mm, degrees):\n"
    "           --nozzle-standoff (10) --nozzle-tip-diameter (10) --nozzle-cone-angle\n"
    "           (half-angle, 30) --nozzle-body-diameter (50) --nozzle-body-length (200)\n"
    "           --nozzle-margin (2, at most half the standoff, at least 5e-4 of the part's\n"
    "           diagonal), --nozzle-max-lean (30: where a layer's nozzle still collides, the\n"
    "           tool axis may lean this far from its normal to clear; 0: never);\n"
    "           --no-plate-check: the build plate is no obstacle.\n"
    "           --gcode OUT.ngc also writes the 5-axis program (LinuxCNC, tilting rotary table\n"
    "           XYZAC, xyzac-trt-kins; X Y Z in the part's coordinates): machine options\n"
    "           --a-limits MIN,MAX (degrees, default -100,50), --c-limits MIN,MAX (-36000,36000),\n"
    "           --feed MM/MIN (600, at the reference thickness), --reference-thickness MM (0:\n"
    "           half-way between the thinnest and thickest deposit), --max-feed-ratio R (4: the\n"
    "           feed within feed/R to feed*R as the thickness varies; 1: constant), --clearance\n"
    "           MM (2: retract along the tool axis), --deposit-output N (0: M62/M63 P0);\n"
    "           the machine's travel, mm: --x-limits MIN,MAX, --y-limits, --z-limits (the\n"
    "           joints' limits; none by default: not checked; past one, an error), where the\n"
    "           part sits: --work-offset X,Y,Z (G54, 0,0,0), and xyzac-trt-kins' pins:\n"
    "           --rot-point X,Y,Z (0,0,0), --rot-offset Y,Z (0,0), --tool-length MM (0).\n"
    "FILE       .step/.stp, .iges/.igs, .brep/.brp (one closed solid) or .stl/.off (a closed "
    "mesh)\n"
    "--json     write JSON instead of text, to OUT.json or standard output\n"
    "--progress report how far decomposing and slicing are on standard error: a line at each\n"
    "           new stage and at most one a second within one, then 100 %. (Ctrl-C stops.)\n"
    "--deflection MM  chordal deflection for tessellating a solid (default: derived from its "
    "size);\n"
    "           a mesh is cut as it is (slice refuses the option for one)\n";

// --progress: the stage and the per cent done on standard error, a line at each new stage and at
// most one a second within a stage (a log stays short), and a last line at 100 %.
mas::Progress stderr_progress() {
    struct State {
        std::string stage;
        std::chrono::steady_clock::time_point last;
        bool any = false, done = false;
    };
    auto st = std::make_shared<State>();
    return mas::Progress([st](double fraction, const std::string& stage) {
        const auto now = std::chrono::steady_clock::now();
        if (st->done) return;
        st->done = fraction >= 1.0;
        if (!st->done && (stage.empty() || (st->any && stage == st->stage &&
                                            now - st->last < std::chrono::seconds(1))))
            return;
        st->any = true;
        st->stage = stage;
        st->last = now;
        std::fprintf(stderr, "%3.0f %% %s\n", 100.0 * fraction, st->done ? "done" : stage.c_str());
        std::fflush(stderr);
    });
}

struct UsageError : std::runtime_error {
    using std::runtime_error::runtime_error;
};

// A value the command line gives in the right form but out of its range: refused as the engine
// refuses it (invalid_argument, exit status 1), before the part is read.
[[noreturn]] void out_of_range(const std::string& message) {
    throw mas::Error(mas::ErrorCode::InvalidArgument, message);
}

double parse_number(const std::string& text, const std::string& what) {
    std::size_t used = 0;
    double v = 0.0;
    try {
        v = std::stod(text, &used);
    } catch (const std::exception&) {
        used = 0;
    }
    if (used != text.size() || text.empty())
        throw UsageError(what + " must be a number, got '" + text + "'");
    if (!std::isfinite(v)) throw UsageError(what + " must be finite, got '" + text + "'");
    return v;
}

// `count` comma-separated numbers, `form` ("X,Y,Z") naming them in the message.
std::vector<double> parse_numbers(const std::string& text, std::size_t count,
                                  const std::string& what, const std::string& form) {
    std::vector<std::string> parts;
    std::stringstream in(text);
    for (std::string item; std::getline(in, item, ',');) parts.push_back(item);
    if (parts.size() != count || (!text.empty() && text.back() == ','))
        throw UsageError(what + " must be " + form + ", got '" + text + "'");
    std::vector<double> out;
    for (const auto& part : parts) out.push_back(parse_number(part, what));
    return out;
}

Eigen::Vector3d parse_vector(const std::string& text, const std::string& what) {
    const std::vector<double> v = parse_numbers(text, 3, what, "X,Y,Z");
    return {v[0], v[1], v[2]};
}

// Minimal JSON output: numbers to 15 significant digits (the engine's doubles within 1e-15).
std::string num(double v) {
    std::ostringstream s;
    s << std::setprecision(15) << (v == 0.0 ? 0.0 : v);  // never -0
    return s.str();
}

std::string vec(const Eigen::Vector3d& v) {
    return "[" + num(v.x()) + ", " + num(v.y()) + ", " + num(v.z()) + "]";
}

// The G-code's routes that meet what is deposited, as JSON objects.
std::string travel_collisions_json(const mas::GcodeStats& gs) {
    std::string out;
    for (std::size_t i = 0; i < gs.travel_collisions.size(); ++i) {
        const mas::TravelCollision& c = gs.travel_collisions[i];
        out += std::string(i ? ", " : "") + "{\"layer\": " + std::to_string(c.layer) +
               ", \"obstacle_layer\": " + std::to_string(c.obstacle_layer) +
               ", \"nozzle_at\": " + vec(c.nozzle_at) + ", \"obstacle\": " + vec(c.obstacle) + "}";
    }
    return out;
}

std::string quoted(const std::string& text) {
    std::string out = "\"";
    for (char c : text) {
        if (c == '"' || c == '\\') {
            out += '\\';
            out += c;
        } else if (static_cast<unsigned char>(c) < 0x20) {
            char buf[8];
            std::snprintf(buf, sizeof buf, "\\u%04x", c);
            out += buf;
        } else {
            out += c;
        }
    }
    return out + "\"";
}

// A command line: FILE, --json [OUT], and `--name value` options a command allows.
struct Args {
    std::string file;
    bool json = false;
    std::string json_path;  // empty: stdout
    std::map<std::string, std::string> options;

    bool has(const std::string& name) const { return options.count(name) > 0; }
    double number(const std::string& name, double fallback) const {
        return has(name) ? parse_number(options.at(name), name) : fallback;
    }
    // A count: a whole number within int's range (range checks beyond that are the engine's).
    int integer(const std::string& name, int fallback) const {
        if (!has(name)) return fallback;
        const double v = parse_number(options.at(name), name);
        if (v != std::floor(v) || std::abs(v) > 1e9)
            throw UsageError(name + " must be a whole number, got '" + options.at(name) + "'");
        return int(v);
    }
    // Whole numbers separated by commas ("1,3"); none when the option is not given.
    std::vector<int> integers(const std::string& name) const {
        std::vector<int> out;
        if (!has(name)) return out;
        std::istringstream in(options.at(name));
        for (std::string item; std::getline(in, item, ',');) {
            const double v = parse_number(item, name);
            if (v != std::floor(v) || std::abs(v) > 1e9)
                throw UsageError(name + " must be whole numbers separated by commas, got '" +
                                 options.at(name) + "'");
            out.push_back(int(v));
        }
        return out;
    }
};

Args parse_args(const std::vector<std::string>& args, const std::set<std::string>& allowed) {
    Args a;
    for (std::size_t i = 0; i < args.size(); ++i) {
        const std::string& arg = args[i];
        if (arg == "--json") {
            a.json = true;
            // FILE comes first; after it, a following non-option argument is the output path.
            if (!a.file.empty() && i + 1 < args.size() && args[i + 1].rfind("-", 0) != 0)
                a.json_path = args[++i];
        } else if (allowed.count(arg)) {
            // A value is never an option ("--gcode --json" names no file "--json").
            if (i + 1 >= args.size() || args[i + 1].rfind("--", 0) == 0)
                throw UsageError(arg + " needs a value");
            a.options[arg] = args[++i];
        } else if (arg.rfind("--", 0) == 0) {
            throw UsageError("unknown option " + arg);
        } else if (a.file.empty()) {
            a.file = arg;
        } else {
            throw UsageError("unexpected argument '" + arg + "'");
        }
    }
    if (a.file.empty()) throw UsageError("no input FILE given");
    std::error_code same;
    if (!a.json_path.empty() && std::filesystem::equivalent(a.json_path, a.file, same))
        throw UsageError("--json " + a.json_path + " would overwrite the input FILE");
    return a;
}

// The part's closed mesh and the deflection it was tessellated with (0 for a mesh file).
struct Part {
    mas::Model model;
    double deflection_mm = 0.0;
    mas::TriangleMesh mesh;

    const char* kind() const { return model.kind == mas::Model::Kind::Solid ? "solid" : "mesh"; }
};

Part load_part(const Args& a) {
    const double deflection = a.number("--deflection", 0.0);
    if (deflection < 0.0)
        out_of_range("--deflection must be positive (or 0 for automatic), got " +
                     mas::format_number(deflection));
    Part part;
    part.model = mas::read_model(a.file);
    mas::TessellationParams tp;
    tp.deflection_mm = deflection;
    if (part.model.kind == mas::Model::Kind::Solid)
        part.deflection_mm = mas::effective_deflection(part.model.shape, tp);
    part.mesh = mas::model_mesh(part.model, tp);
    return part;
}

// Writes what `write` puts out to the --json file, or to standard output. A file is written whole
// or not at all: into a new file beside it, renamed over it once complete, so that a failure while
// writing (a full disk, an error half way) leaves what was there before, and no partial file. A
// path that is there and is no regular file (a device, a pipe) is written directly.
// Writes `path` whole or not at all: through a partial file renamed over it (a device or a pipe
// is written directly).
void write_file(const std::string& path, const std::function<void(std::ostream&)>& write) {
    namespace fs = std::filesystem;
    const mas::Error cannot_write(mas::ErrorCode::WriteFailed, path + ": cannot write the file");
    std::error_code ec;
    const fs::file_status status = fs::status(path, ec);
    if (fs::exists(status) && !fs::is_regular_file(status)) {
        std::ofstream direct(path);
        if (!direct) throw cannot_write;
        write(direct);
        direct.close();
        if (!direct) throw cannot_write;
        return;
    }
    // Through a symbolic link, the file it names is replaced, not the link.
    std::error_code resolved;
    const fs::path target = fs::exists(status) ? fs::canonical(path, resolved) : fs::path(path);
    if (resolved) throw cannot_write;
    fs::path partial;
    for (int k = 0;; ++k) {
        partial = target;
        partial += ".partial-" + std::to_string(::getpid()) + "-" + std::to_string(k);
        if (!fs::exists(fs::symlink_status(partial, ec))) break;
    }
    std::ofstream file(partial);
    if (!file) throw cannot_write;  // nothing made: the path is left as it was
    try {
        write(file);
        file.close();
        std::error_code renamed;
        if (file) fs::rename(partial, target, renamed);
        if (!file || renamed) throw cannot_write;
    } catch (...) {
        file.close();
        fs::remove(partial, ec);
        throw;
    }
}

void write_output(const Args& a, const std::function<void(std::ostream&)>& write) {
    if (a.json && !a.json_path.empty())
        write_file(a.json_path, write);
    else
        write(std::cout);
}

void write_output(const Args& a, const std::string& text) {
    write_output(a, [&](std::ostream& out) { out << text; });
}

int run_sections(const std::vector<std::string>& args) {
    const Args a = parse_args(args, {"--normal", "--step", "--deflection"});
    const double step_mm = a.number("--step", 1.0);
    if (!(step_mm > 0.0))
        out_of_range("--step must be positive, got " + mas::format_number(step_mm));
    const Eigen::Vector3d normal = a.has("--normal")
                                       ? parse_vector(a.options.at("--normal"), "--normal")
                                       : Eigen::Vector3d(0, 0, 1);
    if (normal.norm() < 1e-12) out_of_range("--normal must not be the zero vector");
    const Part part = load_part(a);
    const mas::TriangleMesh& mesh = part.mesh;
    const double deflection = part.deflection_mm;
    const auto planes = mas::parallel_planes(mesh, normal, step_mm);
    const Eigen::Vector3d n = planes.front().normal;
    // Only areas, centroids and counts are written: the planes are cut a few million section
    // points at a time, so that memory stays bounded however fine the step.
    constexpr std::size_t kPointsPerCut = 4000000;
    const std::vector<std::size_t> points = mas::section_point_counts(mesh, planes);
    const auto each_section = [&](const auto& f) {
        for (std::size_t begin = 0, end = 0; begin < planes.size(); begin = end) {
            for (std::size_t held = 0;
                 end < planes.size() && (end == begin || held + points[end] <= kPointsPerCut);
                 ++end)
                held += points[end];
            const auto cut = mas::slice_mesh(
                mesh, std::vector<mas::Plane>(planes.begin() + std::ptrdiff_t(begin),
                                              planes.begin() + std::ptrdiff_t(end)));
            for (std::size_t i = 0; i < cut.size(); ++i) f(begin + i, cut[i]);
        }
    };

    write_output(a, [&](std::ostream& out) {
        if (a.json) {
            out << "{\n  \"file\": " << quoted(a.file) << ",\n  \"kind\": " << quoted(part.kind())
                << ",\n  \"triangles\": " << mesh.triangles.size()
                << ",\n  \"deflection_mm\": " << num(deflection) << ",\n  \"normal\": " << vec(n)
                << ",\n  \"step_mm\": " << num(step_mm) << ",\n  \"sections\": [";
            each_section([&](std::size_t i, const mas::Section& s) {
                out << (i ? "," : "") << "\n    {\"offset_mm\": " << num(n.dot(s.plane.origin))
                    << ", \"area_mm2\": " << num(s.area) << ", \"centroid\": " << vec(s.centroid)
                    << ", \"regions\": [";
                for (std::size_t k = 0; k < s.regions.size(); ++k) {
                    const auto& r = s.regions[k];
                    out << (k ? ", " : "") << "{\"area_mm2\": " << num(r.area)
                        << ", \"centroid\": " << vec(r.centroid)
                        << ", \"holes\": " << r.shape.holes.size() << "}";
                }
                out << "]}";
            });
            out << "\n  ]\n}\n";
        } else {
            out << "# " << a.file << ": " << part.kind() << ", " << mesh.triangles.size()
                << " triangles";
            if (deflection > 0.0) out << ", deflection " << num(deflection) << " mm";
            out << "\n# normal " << num(n.x()) << "," << num(n.y()) << "," << num(n.z())
                << ", step " << num(step_mm) << " mm, " << planes.size() << " sections\n";
            out << "# offset_mm regions holes area_mm2 centroid_x centroid_y centroid_z\n";
            each_section([&](std::size_t, const mas::Section& s) {
                std::size_t holes = 0;
                for (const auto& r : s.regions) holes += r.shape.holes.size();
                out << std::fixed << std::setprecision(4) << n.dot(s.plane.origin) << " "
                    << s.regions.size() << " " << holes << " " << s.area << " " << s.centroid.x()
                    << " " << s.centroid.y() << " " << s.centroid.z() << "\n";
            });
        }
    });
    return 0;
}

const char* link_kind(mas::AxisLink::Kind k) {
    return k == mas::AxisLink::Kind::Connecting ? "connecting" : "step";
}

const std::set<std::string> kAxisOptions = {
    "--step",  "--distance-threshold", "--eps", "--break-angle", "--base-z",
    "--frame", "--deflection"};

mas::AxisParams axis_params(const Args& a) {
    mas::AxisParams p;
    p.step_mm = a.number("--step", 0.0);
    p.distance_threshold_mm = a.number("--distance-threshold", 0.0);
    p.eps_mm = a.number("--eps", p.eps_mm);
    p.break_angle_deg = a.number("--break-angle", p.break_angle_deg);
    p.base_z_mm = a.number("--base-z", p.base_z_mm);
    p.frame_deg = a.number("--frame", p.frame_deg);
    if (p.step_mm < 0.0)
        out_of_range("--step must be positive (or 0 for derived), got " +
                     mas::format_number(p.step_mm));
    if (p.distance_threshold_mm < 0.0)
        out_of_range("--distance-threshold must be positive (or 0 for derived), got " +
                     mas::format_number(p.distance_threshold_mm));
    return p;
}

// The part's centroidal axis, knowing the deflection its mesh was tessellated with.
mas::CentroidalAxis axis_of(const Part& part, const mas::AxisParams& params) {
    mas::CentroidalAxis axis = mas::centroidal_axis(part.mesh, params);
    axis.deflection_mm = part.deflection_mm;
    return axis;
}

int run_axis(const std::vector<std::string>& args) {
    const Args a = parse_args(args, kAxisOptions);
    const mas::AxisParams p = axis_params(a);
    const Part part = load_part(a);
    const mas::CentroidalAxis axis = axis_of(part, p);
    const mas::AxisParams& used = axis.params;

    std::ostringstream out;
    if (a.json) {
        out << "{\n  \"file\": " << quoted(a.file) << ",\n  \"kind\": " << quoted(part.kind())
            << ",\n  \"triangles\": " << part.mesh.triangles.size()
            << ",\n  \"deflection_mm\": " << num(part.deflection_mm)
            << ",\n  \"params\": {\"step_mm\": " << num(used.step_mm)
            << ", \"distance_threshold_mm\": " << num(used.distance_threshold_mm)
            << ", \"eps_mm\": " << num(used.eps_mm)
            << ", \"break_angle_deg\": " << num(used.break_angle_deg)
            << ", \"base_z_mm\": " << num(used.base_z_mm)
            << ", \"frame_deg\": " << num(used.frame_deg) << "}"
            << ",\n  \"searched_volume_mm3\": " << num(axis.searched_volume_mm3)
            << ",\n  \"nodes\": [";
        for (std::size_t i = 0; i < axis.nodes.size(); ++i) {
            const auto& n = axis.nodes[i];
            out << (i ? "," : "") << "\n    {\"position\": " << vec(n.position)
                << ", \"normal\": " << vec(n.normal) << ", \"area_mm2\": " << num(n.area)
                << ", \"offset_mm\": " << num(n.offset)
                << ", \"thickness_mm\": " << num(n.thickness)
                << ", \"slab_start_mm\": " << num(n.slab_start) << ", \"branch\": " << n.branch
                << "}";
        }
        out << "\n  ],\n  \"links\": [";
        for (std::size_t i = 0; i < axis.links.size(); ++i) {
            const auto& l = axis.links[i];
            out << (i ? "," : "") << "\n    {\"start\": " << l.start << ", \"end\": " << l.end
                << ", \"kind\": " << quoted(link_kind(l.kind))
                << ", \"is_break\": " << (l.is_break ? "true" : "false")
                << ", \"turn_deg\": " << num(l.turn_deg) << "}";
        }
        out << "\n  ],\n  \"branches\": [";
        for (std::size_t i = 0; i < axis.branches.size(); ++i) {
            const auto& b = axis.branches[i];
            out << (i ? "," : "") << "\n    {\"parent\": " << b.parent
                << ", \"direction\": " << vec(b.direction) << ", \"nodes\": [";
            for (std::size_t k = 0; k < b.nodes.size(); ++k) out << (k ? ", " : "") << b.nodes[k];
            out << "], \"parent_node\": " << b.parent_node << ", \"first_link\": " << b.first_link
                << ", \"depth\": " << b.depth << ", \"merged_into\": " << b.merged_into << "}";
        }
        out << "\n  ]\n}\n";
    } else {
        int breaks = 0;
        for (const auto& l : axis.links) breaks += l.is_break;
        out << "# " << a.file << ": " << part.kind() << ", " << part.mesh.triangles.size()
            << " triangles\n# step " << num(used.step_mm) << " mm, distance threshold "
            << num(used.distance_threshold_mm) << " mm, frame " << num(used.frame_deg)
            << " degrees about Z: " << axis.nodes.size() << " nodes, " << axis.links.size()
            << " links (" << breaks << " breaks), " << axis.branches.size()
            << " branches\n# branch parent parent_node direction nodes first_node last_node\n";
        for (std::size_t i = 0; i < axis.branches.size(); ++i) {
            const auto& b = axis.branches[i];
            const auto& first = axis.nodes[std::size_t(b.nodes.front())].position;
            const auto& last = axis.nodes[std::size_t(b.nodes.back())].position;
            out << i << " " << b.parent << " " << b.parent_node << " " << num(b.direction.x())
                << "," << num(b.direction.y()) << "," << num(b.direction.z()) << " "
                << b.nodes.size() << std::fixed << std::setprecision(4) << " " << first.x() << ","
                << first.y() << "," << first.z() << " " << last.x() << "," << last.y() << ","
                << last.z() << "\n"
                << std::defaultfloat;
        }
    }
    write_output(a, out.str());
    return 0;
}

// One component as `decompose` reports it: a solid's, or a mesh's piece.
struct ComponentRow {
    int parent = -1;
    Eigen::Vector3d build_direction = Eigen::Vector3d::UnitZ();
    bool has_base_face = false;
    Eigen::Vector3d base_origin = Eigen::Vector3d::Zero();
    Eigen::Vector3d base_normal = -Eigen::Vector3d::UnitZ();
    int branch = 0;
    int break_link = -1;
    std::string rule;
    bool turned = false;  // cut square to its branch's line (Component::turned)
    double volume_mm3 = 0.0;
    std::string file;  // where --step-dir or --stl-dir wrote it, empty when not written
};

// With the folder option `option` given, creates the folder and writes component i through
// `write(i, path)` as DIR/component_NNN.`extension`; returns the paths (empty without it).
std::vector<std::string> write_components(
    const Args& a, const std::string& option, std::size_t count, const std::string& extension,
    const std::function<void(std::size_t, const std::string&)>& write) {
    std::vector<std::string> files(count);
    if (!a.has(option)) return files;
    const std::string dir = a.options.at(option);
    std::error_code ec;
    std::filesystem::create_directories(dir, ec);
    if (ec) throw mas::Error(mas::ErrorCode::WriteFailed, dir + ": cannot create the folder");
    for (std::size_t i = 0; i < count; ++i) {
        std::ostringstream name;
        name << "component_" << std::setw(3) << std::setfill('0') << i + 1 << "." << extension;
        files[i] = (std::filesystem::path(dir) / name.str()).string();
        write(i, files[i]);
    }
    return files;
}

// What `decompose` prints: the components (and the files written, under `file_key`) and the
// notes, as JSON or text.
void report_components(const Args& a, const Part& part, double part_volume_mm3,
                       const mas::CentroidalAxis& axis, const std::vector<ComponentRow>& rows,
                       const std::vector<std::string>& notes, const std::string& file_key) {
    const bool files = std::any_of(rows.begin(), rows.end(),
                                   [](const ComponentRow& r) { return !r.file.empty(); });
    std::ostringstream out;
    if (a.json) {
        out << "{\n  \"file\": " << quoted(a.file) << ",\n  \"kind\": " << quoted(part.kind())
            << ",\n  \"part_volume_mm3\": " << num(part_volume_mm3)
            << ",\n  \"axis\": {\"step_mm\": " << num(axis.params.step_mm)
            << ", \"nodes\": " << axis.nodes.size() << ", \"branches\": " << axis.branches.size()
            << "},\n  \"components\": [";
        for (std::size_t i = 0; i < rows.size(); ++i) {
            const ComponentRow& c = rows[i];
            out << (i ? "," : "") << "\n    {\"parent\": " << c.parent
                << ", \"build_direction\": " << vec(c.build_direction)
                << ", \"has_base_face\": " << (c.has_base_face ? "true" : "false")
                << ", \"base_origin\": " << vec(c.base_origin)
                << ", \"base_normal\": " << vec(c.base_normal) << ", \"branch\": " << c.branch
                << ", \"break_link\": " << c.break_link << ", \"rule\": " << quoted(c.rule)
                << ", \"turned\": " << (c.turned ? "true" : "false")
                << ", \"volume_mm3\": " << num(c.volume_mm3);
            if (!c.file.empty()) out << ", \"" << file_key << "\": " << quoted(c.file);
            out << "}";
        }
        out << "\n  ],\n  \"notes\": [";
        for (std::size_t i = 0; i < notes.size(); ++i)
            out << (i ? ", " : "") << "\n    " << quoted(notes[i]);
        out << "\n  ]\n}\n";
    } else {
        for (const auto& note : notes) out << "# note: " << note << "\n";
        out << "# " << a.file << ": " << rows.size() << " components, axis step "
            << num(axis.params.step_mm) << " mm\n# component parent rule build_direction volume_mm3"
            << (files ? " " + file_key : "") << "\n";
        for (std::size_t i = 0; i < rows.size(); ++i) {
            const ComponentRow& c = rows[i];
            out << i << " " << c.parent << " " << c.rule << " " << num(c.build_direction.x()) << ","
                << num(c.build_direction.y()) << "," << num(c.build_direction.z()) << " "
                << num(c.volume_mm3);
            if (!c.file.empty()) out << " " << c.file;
            out << "\n";
        }
    }
    write_output(a, out.str());
}

// An option that applies to a solid, given with a mesh file: `why` names the option and what a mesh
// does instead.
[[noreturn]] void refused_for_a_mesh(const Args& a, const std::string& why) {
    throw mas::Error(mas::ErrorCode::InvalidArgument, why + " (" + a.file + " is a mesh)");
}

// The pieces a mesh is split into (decompose_mesh), reported as a solid's components are.
int decompose_mesh_part(const Args& a, const Part& part, const mas::AxisParams& ap,
                        const mas::DecomposeParams& dp, bool no_fallback, bool report) {
    for (const char* option : {"--face-angle", "--concave-angle", "--step-dir"})
        if (a.has(option))
            refused_for_a_mesh(a, std::string(option) +
                                      " applies to a solid: a mesh has no faces "
                                      "and is split at section planes");
    if (no_fallback)
        refused_for_a_mesh(a,
                           "--no-fallback applies to a solid: a mesh is split at section planes "
                           "only");
    const mas::CentroidalAxis axis = axis_of(part, ap);
    mas::MeshDecomposeParams mp;
    mp.min_component_height_mm = dp.min_component_height_mm;
    mp.max_tilt_deg = dp.max_tilt_deg;
    mp.keep_branches = dp.keep_branches;
    mp.square_branches = dp.square_branches;
    const mas::MeshDecomposition d =
        mas::decompose_mesh(part.mesh, axis, mp, report ? stderr_progress() : mas::Progress());
    const std::vector<std::string> files = write_components(
        a, "--stl-dir", d.components.size(), "stl", [&](std::size_t i, const std::string& path) {
            mas::write_stl(d.components[i].mesh, path);
        });
    std::vector<ComponentRow> rows(d.components.size());
    for (std::size_t i = 0; i < rows.size(); ++i) {
        const mas::ComponentMesh& c = d.components[i];
        ComponentRow& r = rows[i];
        r.parent = c.parent;
        r.build_direction = c.base.normal;
        r.has_base_face = c.parent >= 0;
        r.base_origin = c.base.origin;
        r.base_normal = -c.base.normal;
        r.branch = c.branch;
        r.rule = c.parent < 0 ? "root" : c.bridge ? "bridge" : "section_plane";
        r.turned = c.turned;
        r.volume_mm3 = mas::mesh_volume(c.mesh);
        r.file = files[i];
    }
    report_components(a, part, mas::mesh_volume(part.mesh), axis, rows, d.notes, "stl_file");
    return 0;
}

int run_decompose(const std::vector<std::string>& args) {
    std::set<std::string> allowed = kAxisOptions;
    allowed.insert({"--face-angle", "--concave-angle", "--min-height", "--max-tilt", "--step-dir",
                    "--stl-dir", "--keep-branches", "--square-branches"});
    // --no-fallback takes no value: take it out before the common parser sees it.
    std::vector<std::string> rest;
    bool fallback = true, report = false;
    for (const auto& arg : args) {
        if (arg == "--no-fallback")
            fallback = false;
        else if (arg == "--progress")
            report = true;
        else
            rest.push_back(arg);
    }
    const Args a = parse_args(rest, allowed);
    const mas::AxisParams ap = axis_params(a);
    mas::DecomposeParams dp;
    dp.face_angle_deg = a.number("--face-angle", dp.face_angle_deg);
    dp.concave_angle_deg = a.number("--concave-angle", dp.concave_angle_deg);
    dp.min_component_height_mm = a.number("--min-height", dp.min_component_height_mm);
    dp.max_tilt_deg = a.number("--max-tilt", dp.max_tilt_deg);
    dp.section_plane_fallback = fallback;
    for (const int b : a.integers("--keep-branches"))
        dp.keep_branches.push_back({b, "kept in its father, as asked (--keep-branches)"});
    dp.square_branches = a.integers("--square-branches");
    const Part part = load_part(a);
    if (part.model.kind != mas::Model::Kind::Solid)
        return decompose_mesh_part(a, part, ap, dp, !fallback, report);
    if (a.has("--stl-dir"))
        throw mas::Error(mas::ErrorCode::InvalidArgument,
                         "--stl-dir writes a mesh's pieces: a solid's components are written with "
                         "--step-dir (" +
                             a.file + " is a solid)");
    const mas::Shape solid = part.model.shape.single_solid(a.file);
    const mas::CentroidalAxis axis = axis_of(part, ap);
    const mas::Decomposition d =
        mas::decompose(solid, axis, dp, report ? stderr_progress() : mas::Progress());

    const std::vector<std::string> files = write_components(
        a, "--step-dir", d.components.size(), "step", [&](std::size_t i, const std::string& path) {
            mas::write_step(d.components[i].solid, path);
        });
    std::vector<ComponentRow> rows(d.components.size());
    for (std::size_t i = 0; i < rows.size(); ++i) {
        const auto& c = d.components[i];
        ComponentRow& r = rows[i];
        r.parent = c.parent;
        r.build_direction = c.build_direction;
        r.has_base_face = c.has_base_face;
        r.base_origin = c.base_origin;
        r.base_normal = c.base_normal;
        r.branch = c.branch;
        r.break_link = c.break_link;
        r.rule = mas::to_string(c.rule);
        r.turned = c.turned;
        r.volume_mm3 = c.volume_mm3;
        r.file = files[i];
    }
    report_components(a, part, solid.info().volume_mm3, axis, rows, d.notes, "step_file");
    return 0;
}

const std::set<std::string> kSliceOptions = {"--min-layer",
                                             "--max-layer",
                                             "--max-volume-difference",
                                             "--eps-angle",
                                             "--overhang-angle",
                                             "--max-tilt",
                                             "--volume-samples",
                                             "--bead-width",
                                             "--overlap",
                                             "--contours",
                                             "--infill",
                                             "--raster-angle",
                                             "--raster-angle-step",
                                             "--min-feature",
                                             "--fill-holes",
                                             "--nozzle-standoff",
                                             "--nozzle-tip-diameter",
                                             "--nozzle-cone-angle",
                                             "--nozzle-body-diameter",
                                             "--nozzle-body-length",
                                             "--nozzle-margin",
                                             "--nozzle-max-lean"};

const std::set<std::string> kMachineOptions = {
    "--a-limits",       "--c-limits",   "--feed",           "--reference-thickness",
    "--max-feed-ratio", "--clearance",  "--deposit-output", "--x-limits",
    "--y-limits",       "--z-limits",   "--work-offset",    "--rot-point",
    "--rot-offset",     "--tool-length"};

// The machine for --gcode; its options without --gcode are a usage error.
mas::MachineParams machine_params(const Args& a) {
    mas::MachineParams m;
    if (!a.has("--gcode")) {
        for (const auto& option : kMachineOptions)
            if (a.has(option)) throw UsageError(option + " is for the G-code: give --gcode OUT");
        return m;
    }
    if (a.has("--a-limits")) {
        const auto v = parse_numbers(a.options.at("--a-limits"), 2, "--a-limits", "MIN,MAX");
        m.a_min_deg = v[0];
        m.a_max_deg = v[1];
    }
    if (a.has("--c-limits")) {
        const auto v = parse_numbers(a.options.at("--c-limits"), 2, "--c-limits", "MIN,MAX");
        m.c_min_deg = v[0];
        m.c_max_deg = v[1];
    }
    m.feed_mm_min = a.number("--feed", m.feed_mm_min);
    m.reference_thickness_mm = a.number("--reference-thickness", m.reference_thickness_mm);
    m.max_feed_ratio = a.number("--max-feed-ratio", m.max_feed_ratio);
    m.clearance_mm = a.number("--clearance", m.clearance_mm);
    m.deposit_output = a.integer("--deposit-output", m.deposit_output);
    for (int axis = 0; axis < 3; ++axis) {
        const std::string option = std::string("--") + "xyz"[axis] + "-limits";
        if (!a.has(option)) continue;
        const auto v = parse_numbers(a.options.at(option), 2, option, "MIN,MAX");
        m.travel_min[axis] = v[0];
        m.travel_max[axis] = v[1];
    }
    if (a.has("--work-offset"))
        m.work_offset = parse_vector(a.options.at("--work-offset"), "--work-offset");
    if (a.has("--rot-point"))
        m.rot_point = parse_vector(a.options.at("--rot-point"), "--rot-point");
    if (a.has("--rot-offset")) {
        const auto v = parse_numbers(a.options.at("--rot-offset"), 2, "--rot-offset", "Y,Z");
        m.rot_offset_y_mm = v[0];
        m.rot_offset_z_mm = v[1];
    }
    m.tool_length_mm = a.number("--tool-length", m.tool_length_mm);
    mas::validate(m);
    const std::string& path = a.options.at("--gcode");
    std::error_code same;
    if (std::filesystem::equivalent(path, a.file, same))
        throw UsageError("--gcode " + path + " would overwrite the input FILE");
    namespace fs = std::filesystem;
    if (a.json && !a.json_path.empty() &&
        fs::weakly_canonical(path, same) == fs::weakly_canonical(a.json_path, same))
        throw UsageError("--gcode and --json name the same file " + path);
    // Before the slicing: a folder that is not there, or a folder named, fails now, not after
    // minutes.
    if (fs::is_directory(path, same))
        throw mas::Error(mas::ErrorCode::WriteFailed,
                         path + ": cannot write the file: it is a folder");
    const fs::path folder = fs::path(path).parent_path();
    if (!folder.empty() && !fs::is_directory(folder, same))
        throw mas::Error(mas::ErrorCode::WriteFailed,
                         path + ": cannot write the file: no folder " + folder.string());
    return m;
}

mas::SlicePartParams slice_params(const Args& a) {
    mas::SlicePartParams p;
    mas::LayerParams& l = p.layers;
    l.min_layer_mm = a.number("--min-layer", l.min_layer_mm);
    l.max_layer_mm = a.number("--max-layer", l.max_layer_mm);
    l.max_volume_difference = a.number("--max-volume-difference", l.max_volume_difference);
    l.eps_angle_deg = a.number("--eps-angle", l.eps_angle_deg);
    l.overhang_angle_deg = a.number("--overhang-angle", l.overhang_angle_deg);
    l.max_tilt_deg = a.number("--max-tilt", l.max_tilt_deg);
    l.volume_samples = a.integer("--volume-samples", l.volume_samples);
    mas::PathParams& t = p.paths;
    t.bead_width_mm = a.number("--bead-width", t.bead_width_mm);
    t.overlap = a.number("--overlap", t.overlap);
    t.contour_count = a.integer("--contours", t.contour_count);
    if (a.has("--infill"))
        t.infill = mas::infill_pattern_from_string(a.options.at("--infill").c_str());
    t.raster_angle_deg = a.number("--raster-angle", t.raster_angle_deg);
    t.raster_angle_step_deg = a.number("--raster-angle-step", t.raster_angle_step_deg);
    t.min_feature_mm = a.number("--min-feature", t.min_feature_mm);
    p.tessellation.deflection_mm = a.number("--deflection", 0.0);
    p.fill_holes_up_to_mm = a.number("--fill-holes", 0.0);
    if (!(p.fill_holes_up_to_mm >= 0.0) || !std::isfinite(p.fill_holes_up_to_mm))
        throw mas::Error(
            mas::ErrorCode::InvalidArgument,
            "--fill-holes must be a diameter >= 0 mm, got " + a.options.at("--fill-holes"));
    mas::NozzleParams& n = p.nozzle;
    n.standoff_mm = a.number("--nozzle-standoff", n.standoff_mm);
    n.tip_diameter_mm = a.number("--nozzle-tip-diameter", n.tip_diameter_mm);
    n.cone_angle_deg = a.number("--nozzle-cone-angle", n.cone_angle_deg);
    n.body_diameter_mm = a.number("--nozzle-body-diameter", n.body_diameter_mm);
    n.body_length_mm = a.number("--nozzle-body-length", n.body_length_mm);
    n.margin_mm = a.number("--nozzle-margin", n.margin_mm);
    n.max_lean_deg = a.number("--nozzle-max-lean", n.max_lean_deg);
    return p;
}

void write_points(std::ostream& out, const std::vector<Eigen::Vector3d>& points) {
    out << "[";
    for (std::size_t i = 0; i < points.size(); ++i) out << (i ? ", " : "") << vec(points[i]);
    out << "]";
}

// {"outer": [...], "holes": [[...], ...]} from a region's 3-D loops (outer first).
void write_region(std::ostream& out, const std::vector<std::vector<Eigen::Vector3d>>& loops) {
    out << "{\"outer\": ";
    write_points(out, loops.front());
    out << ", \"holes\": [";
    for (std::size_t h = 1; h < loops.size(); ++h) {
        out << (h > 1 ? ", " : "");
        write_points(out, loops[h]);
    }
    out << "]}";
}

int run_slice(const std::vector<std::string>& args) {
    std::set<std::string> allowed = kAxisOptions;
    allowed.insert(kSliceOptions.begin(), kSliceOptions.end());
    allowed.insert(kMachineOptions.begin(), kMachineOptions.end());
    allowed.insert("--gcode");
    std::vector<std::string> rest;
    bool strict = false, coverage = false, report = false, no_plate = false, whole = false,
         allow_collisions = false;
    for (const auto& arg : args) {
        if (arg == "--strict")
            strict = true;
        else if (arg == "--one-component")
            whole = true;
        else if (arg == "--allow-collisions")
            allow_collisions = true;
        else if (arg == "--no-plate-check")
            no_plate = true;
        else if (arg == "--measure-coverage")
            coverage = true;
        else if (arg == "--progress")
            report = true;
        else
            rest.push_back(arg);
    }
    const Args a = parse_args(rest, allowed);
    const mas::AxisParams ap = axis_params(a);
    mas::SlicePartParams sp = slice_params(a);
    sp.layers.strict = strict;
    sp.paths.measure_coverage = coverage;
    sp.nozzle.check_plate = !no_plate;
    sp.split_mesh = !whole;
    sp.avoid_collisions = !allow_collisions;
    mas::validate(sp.layers);
    mas::validate(sp.paths);
    mas::validate(sp.nozzle);
    const mas::MachineParams machine = machine_params(a);
    // The machine given, and no reach: the layers tilt no further than its table turns them.
    if (!a.has("--max-tilt") && a.has("--a-limits"))
        sp.layers.max_tilt_deg =
            std::clamp(std::max(-machine.a_min_deg, machine.a_max_deg), 90.0, 180.0);
    const Part part = load_part(a);
    if (part.model.kind == mas::Model::Kind::Mesh && a.has("--deflection"))
        // As the scripting API's slice() refuses it, before the axis is marched.
        refused_for_a_mesh(a, "--deflection tessellates a solid: a mesh is sliced as it is");
    const mas::CentroidalAxis axis = axis_of(part, ap);
    mas::SlicedPart r;
    const mas::Progress progress = report ? stderr_progress() : mas::Progress();
    if (part.model.kind == mas::Model::Kind::Solid) {
        if (whole)
            throw mas::Error(mas::ErrorCode::InvalidArgument,
                             "--one-component applies to a mesh: a solid is decomposed (" + a.file +
                                 " is a solid)");
        const mas::Shape solid = part.model.shape.single_solid(a.file);
        // Why a branch got no sub-component of its own (material hanging from above stays in
        // its father, overhanging) comes first in the notes, before the holes'.
        mas::DecomposeParams dp;  // no component thinner than a layer, none past the reach
        dp.min_component_height_mm = sp.layers.min_layer_mm;
        dp.max_tilt_deg = sp.layers.max_tilt_deg;
        mas::Decomposition d;
        r = mas::slice_solid_part(solid, axis, dp, sp, d, progress);
    } else {
        r = mas::slice_mesh_part(part.mesh, axis, sp, progress);
    }
    mas::GcodeStats gs;
    if (a.has("--gcode")) {
        // The travel is checked against the nozzle and plate the sequence was.
        const mas::TravelNozzle nozzle{sp.nozzle, r.plate};
        const std::string program =
            mas::write_gcode(mas::gcode_layers(r), machine, &gs, {}, &nozzle);
        write_file(a.options.at("--gcode"), [&](std::ostream& file) { file << program; });
    }
    const mas::SliceStats& st = r.stats;
    std::ostringstream out;
    if (a.json) {
        const mas::LayerParams& l = sp.layers;
        const mas::PathParams& t = sp.paths;
        out << "{\n  \"file\": " << quoted(a.file) << ",\n  \"kind\": " << quoted(part.kind())
            << ",\n  \"params\": {\"min_layer\": " << num(l.min_layer_mm)
            << ", \"max_layer\": " << num(l.max_layer_mm)
            << ", \"max_volume_difference\": " << num(l.max_volume_difference)
            << ", \"eps_angle\": " << num(l.eps_angle_deg)
            << ", \"overhang_angle\": " << num(l.overhang_angle_deg)
            << ", \"max_tilt\": " << num(l.max_tilt_deg)
            << ", \"volume_samples\": " << l.volume_samples
            << ", \"strict\": " << (l.strict ? "true" : "false")
            << ", \"bead_width\": " << num(t.bead_width_mm) << ", \"overlap\": " << num(t.overlap)
            << ", \"contour_count\": " << t.contour_count
            << ", \"infill\": " << quoted(mas::to_string(t.infill))
            << ", \"raster_angle\": " << num(t.raster_angle_deg)
            << ", \"raster_angle_step\": " << num(t.raster_angle_step_deg)
            << ", \"min_feature\": " << num(t.min_feature_mm)
            << ", \"measure_coverage\": " << (t.measure_coverage ? "true" : "false")
            << ", \"fill_holes\": " << num(sp.fill_holes_up_to_mm)
            << ", \"split_mesh\": " << (sp.split_mesh ? "true" : "false")
            << ", \"avoid_collisions\": " << (sp.avoid_collisions ? "true" : "false")
            << ", \"nozzle_standoff\": " << num(sp.nozzle.standoff_mm)
            << ", \"nozzle_tip_diameter\": " << num(sp.nozzle.tip_diameter_mm)
            << ", \"nozzle_cone_angle\": " << num(sp.nozzle.cone_angle_deg)
            << ", \"nozzle_body_diameter\": " << num(sp.nozzle.body_diameter_mm)
            << ", \"nozzle_body_length\": " << num(sp.nozzle.body_length_mm)
            << ", \"nozzle_margin\": " << num(sp.nozzle.margin_mm)
            << ", \"nozzle_max_lean\": " << num(sp.nozzle.max_lean_deg)
            << ", \"check_plate\": " << (sp.nozzle.check_plate ? "true" : "false") << "}"
            << ",\n  \"stats\": {\"layer_count\": " << st.layer_count
            << ", \"min_thickness_mm\": " << num(st.min_thickness_mm)
            << ", \"max_thickness_mm\": " << num(st.max_thickness_mm)
            << ", \"part_volume_mm3\": " << num(st.part_volume_mm3)
            << ", \"deposited_volume_mm3\": " << num(st.deposited_volume_mm3)
            << ", \"material_volume_mm3\": " << num(st.material_volume_mm3)
            << ", \"max_volume_difference\": " << num(st.max_volume_difference)
            << ", \"layers_over_volume_difference\": " << st.layers_over_volume_difference
            << ", \"worst_unsupported_area_mm2\": " << num(st.worst_unsupported_area_mm2)
            << ", \"worst_unsupported_layer\": " << st.worst_unsupported_layer
            << ", \"deposit_length_mm\": " << num(st.deposit_length_mm)
            << ", \"travel_length_mm\": " << num(st.travel_length_mm)
            << ", \"centre_line_passes\": " << st.centre_line_passes
            << ", \"unfilled_features\": " << st.unfilled_features
            << ", \"colliding_layers\": " << st.colliding_layers
            << ", \"component_switches\": " << st.component_switches
            << ", \"leaned_layers\": " << st.leaned_layers
            << ", \"filled_holes\": " << st.filled_holes
            << ", \"filled_volume_mm3\": " << num(st.filled_volume_mm3)
            << "},\n  \"filled_holes\": [";
        for (std::size_t i = 0; i < r.filled_holes.size(); ++i) {
            const mas::FilledHole& h = r.filled_holes[i];
            out << (i ? "," : "") << "\n    {\"component\": " << h.component
                << ", \"centre\": " << vec(h.centre) << ", \"axis\": " << vec(h.axis)
                << ", \"diameter_mm\": " << num(h.diameter_mm)
                << ", \"length_mm\": " << num(h.length_mm) << "}";
        }
        out << (r.filled_holes.empty() ? "" : "\n  ") << "],";
        if (a.has("--gcode"))
            out << "\n  \"gcode\": {\"file\": " << quoted(a.options.at("--gcode"))
                << ", \"lines\": " << gs.lines << ", \"deposit_moves\": " << gs.deposit_moves
                << ", \"feed_limited_moves\": " << gs.feed_limited_moves
                << ", \"reorientations\": " << gs.reorientations << ", \"a_range_deg\": ["
                << num(gs.a_min_deg) << ", " << num(gs.a_max_deg) << "], \"c_range_deg\": ["
                << num(gs.c_min_deg) << ", " << num(gs.c_max_deg)
                << "], \"deposit_length_mm\": " << num(gs.deposit_length_mm)
                << ", \"deposit_time_min\": " << num(gs.deposit_time_min)
                << ", \"rapid_length_mm\": " << num(gs.rapid_length_mm)
                << ", \"reference_thickness_mm\": " << num(gs.reference_thickness_mm)
                << ", \"x_range_mm\": [" << num(gs.machine_min.x()) << ", "
                << num(gs.machine_max.x()) << "], \"y_range_mm\": [" << num(gs.machine_min.y())
                << ", " << num(gs.machine_max.y()) << "], \"z_range_mm\": ["
                << num(gs.machine_min.z()) << ", " << num(gs.machine_max.z()) << "]"
                << ", \"checked_routes\": " << gs.checked_routes
                << ", \"rerouted_travels\": " << gs.rerouted_travels << ", \"travel_collisions\": ["
                << travel_collisions_json(gs) << "]},";
        out << "\n  \"notes\": [";
        for (std::size_t i = 0; i < r.notes.size(); ++i)
            out << (i ? ", " : "") << quoted(r.notes[i]);
        out << "],\n  \"build_order\": [";
        for (std::size_t i = 0; i < r.build_order.size(); ++i)
            out << (i ? ", " : "") << r.build_order[i];
        out << "],\n  \"sequence\": [";
        for (std::size_t i = 0; i < r.sequence.layers.size(); ++i)
            out << (i ? ", " : "") << r.sequence.layers[i];
        out << "],\n  \"collisions\": [";
        for (std::size_t i = 0; i < r.sequence.collisions.size(); ++i) {
            const mas::NozzleCollision& c = r.sequence.collisions[i];
            out << (i ? "," : "") << "\n    {\"layer\": " << c.layer
                << ", \"obstacle_layer\": " << c.obstacle_layer
                << ", \"nozzle_at\": " << vec(c.nozzle_at) << ", \"obstacle\": " << vec(c.obstacle)
                << "}";
        }
        if (!r.sequence.collisions.empty()) out << "\n  ";
        out << "],\n  \"components\": [";
        for (std::size_t i = 0; i < r.components.size(); ++i) {
            const auto& c = r.components[i];
            out << (i ? "," : "") << "\n    {\"component\": " << c.component
                << ", \"first_layer\": " << c.first_layer << ", \"layer_count\": " << c.layer_count
                << ", \"guide_nodes\": " << c.guide_nodes
                << ", \"volume_mm3\": " << num(c.volume_mm3) << "}";
        }
        out << "\n  ],\n  \"layers\": [";
        for (std::size_t i = 0; i < r.layers.size(); ++i) {
            const mas::Layer& l = r.layers[i];
            const mas::LayerToolpaths& tp = r.toolpaths[i];
            out << (i ? "," : "") << "\n    {\"component\": " << l.component
                << ", \"origin\": " << vec(l.plane.origin)
                << ", \"normal\": " << vec(l.plane.normal)
                << ", \"lower_origin\": " << vec(l.lower.origin)
                << ", \"lower_normal\": " << vec(l.lower.normal) << ", \"regions\": [";
            for (std::size_t k = 0; k < l.regions.size(); ++k) {
                out << (k ? ", " : "");
                write_region(out, l.loops_3d(k));
            }
            out << "], \"area_mm2\": " << num(l.area_mm2)
                << ", \"min_thickness_mm\": " << num(l.min_thickness_mm)
                << ", \"max_thickness_mm\": " << num(l.max_thickness_mm)
                << ", \"volume_mm3\": " << num(l.volume_mm3)
                << ", \"material_volume_mm3\": " << num(l.material_volume_mm3)
                << ", \"volume_difference\": " << num(l.volume_difference)
                << ", \"meets_volume_difference\": "
                << (l.meets_volume_difference ? "true" : "false")
                << ", \"unsupported_area_mm2\": " << num(l.unsupported_area_mm2)
                << ", \"unsupported_regions\": [";
            for (std::size_t k = 0; k < l.unsupported.size(); ++k) {
                out << (k ? ", " : "");
                write_region(out, l.unsupported_loops_3d(k));
            }
            out << "]"
                << ", \"outline_length_mm\": " << num(mas::perimeter(l.regions))
                << ", \"axis_node\": " << l.axis_node << ", \"axis_point\": " << vec(l.axis_point)
                << ", \"tool_axis\": " << vec(tp.tool_axis) << ", \"paths\": [";
            for (std::size_t k = 0; k < tp.paths.size(); ++k) {
                const mas::ToolPath& p = tp.paths[k];
                out << (k ? ", " : "") << "\n      {\"kind\": " << quoted(mas::to_string(p.kind))
                    << ", \"region\": " << p.region << ", \"points\": ";
                write_points(out, p.points);
                out << ", \"thickness_mm\": [";
                for (std::size_t j = 0; j < p.thickness_mm.size(); ++j)
                    out << (j ? ", " : "") << num(p.thickness_mm[j]);
                out << "]}";
            }
            out << "], \"centre_line_regions\": [";
            for (std::size_t k = 0; k < tp.centre_line_regions.size(); ++k)
                out << (k ? ", " : "") << tp.centre_line_regions[k];
            out << "], \"unfilled\": [";
            const mas::PlaneFrame frame(l.plane.normal);
            for (std::size_t k = 0; k < tp.unfilled.size(); ++k) {
                const auto& u = tp.unfilled[k];
                out << (k ? ", " : "") << "{\"region\": " << u.region
                    << ", \"area_mm2\": " << num(u.area_mm2)
                    << ", \"centroid\": " << vec(frame.to_3d(u.centroid, l.plane)) << "}";
            }
            out << "], \"deposit_length_mm\": " << num(tp.deposit_length_mm)
                << ", \"travel_length_mm\": " << num(tp.travel_length_mm)
                << ", \"uncovered_area_mm2\": " << num(tp.uncovered_area_mm2) << "}";
        }
        out << "\n  ]\n}\n";
    } else {
        out << "# " << a.file << ": " << r.components.size() << " components, " << st.layer_count
            << " layers, thickness " << num(st.min_thickness_mm) << " to "
            << num(st.max_thickness_mm) << " mm\n# axis: step " << num(axis.params.step_mm)
            << " mm, frame " << num(axis.params.frame_deg)
            << " degrees about Z (build directions and rasters line up with it)\n# deposited "
            << num(st.deposited_volume_mm3) << " of " << num(st.part_volume_mm3)
            << " mm3; worst volume difference " << num(st.max_volume_difference) << " ("
            << st.layers_over_volume_difference
            << " layers over the bound); worst unsupported area "
            << num(st.worst_unsupported_area_mm2) << " mm2\n# paths: " << num(st.deposit_length_mm)
            << " mm deposit, " << num(st.travel_length_mm) << " mm travel, "
            << st.centre_line_passes << " centre-line passes, " << st.unfilled_features
            << " unfilled features\n";
        for (const auto& note : r.notes) out << "# note: " << note << "\n";
        if (a.has("--gcode"))
            out << "# G-code: " << a.options.at("--gcode") << ", " << gs.lines << " lines, "
                << gs.deposit_moves << " deposit moves (" << gs.feed_limited_moves
                << " at a feed limit), A " << num(gs.a_min_deg) << " to " << num(gs.a_max_deg)
                << " deg, C " << num(gs.c_min_deg) << " to " << num(gs.c_max_deg)
                << " deg, deposit time " << num(gs.deposit_time_min) << " min\n# machine: X "
                << num(gs.machine_min.x()) << " to " << num(gs.machine_max.x()) << ", Y "
                << num(gs.machine_min.y()) << " to " << num(gs.machine_max.y()) << ", Z "
                << num(gs.machine_min.z()) << " to " << num(gs.machine_max.z())
                << " mm\n# travel: " << gs.checked_routes << " routes checked against the nozzle, "
                << gs.rerouted_travels << " taken round the part, " << gs.travel_collisions.size()
                << " meeting what is deposited\n";
        for (const mas::TravelCollision& c : gs.travel_collisions)
            out << "#   on the way "
                << (c.layer < 0 ? std::string("off the part")
                                : "to layer " + std::to_string(c.layer))
                << " the nozzle meets "
                << (c.obstacle_layer < 0 ? std::string("the build plate")
                                         : "layer " + std::to_string(c.obstacle_layer))
                << " near " << num(c.obstacle.x()) << "," << num(c.obstacle.y()) << ","
                << num(c.obstacle.z()) << "\n";
        if (!r.filled_holes.empty())
            out << "# deposited solid, to drill afterwards: " << st.filled_holes
                << (st.filled_holes == 1 ? " hole, " : " holes, ") << num(st.filled_volume_mm3)
                << " mm3\n# component centre axis diameter_mm length_mm\n";
        for (const mas::FilledHole& h : r.filled_holes)
            out << "#   " << h.component << " " << num(h.centre.x()) << "," << num(h.centre.y())
                << "," << num(h.centre.z()) << " " << num(h.axis.x()) << "," << num(h.axis.y())
                << "," << num(h.axis.z()) << " " << num(h.diameter_mm) << " " << num(h.length_mm)
                << "\n";
        out << "# build order:";
        for (const int c : r.build_order) out << " " << c;
        auto count = [](long n, const char* one, const char* many) {
            return std::to_string(n) + " " + (n == 1 ? one : many);
        };
        out << "\n# sequence: " << count(long(r.sequence.layers.size()), "layer", "layers") << ", "
            << count(st.component_switches, "switch", "switches") << " between components, "
            << count(r.sequence.interrupted_components, "component", "components")
            << " interrupted; " << count(st.leaned_layers, "layer", "layers")
            << " with the nozzle leaned to clear; " << count(st.colliding_layers, "layer", "layers")
            << " where the nozzle meets what is deposited";
        for (const int i : r.sequence.layers) {
            const mas::Layer& l = r.layers[std::size_t(i)];
            const Eigen::Vector3d& axis = r.sequence.tool_axes[std::size_t(i)];
            if (axis == l.plane.normal) continue;
            out << "\n#   layer " << i << " (component " << l.component << ") leans "
                << num(std::round(std::acos(std::clamp(axis.dot(l.plane.normal), -1.0, 1.0)) *
                                  180.0 / mas::kPi * 1e6) /
                       1e6)
                << " degrees: tool axis " << num(axis.x()) << "," << num(axis.y()) << ","
                << num(axis.z());
        }
        for (const mas::NozzleCollision& c : r.sequence.collisions)
            out << "\n#   layer " << c.layer << " (component "
                << r.layers[std::size_t(c.layer)].component << ") meets "
                << (c.obstacle_layer < 0 ? std::string("the build plate")
                                         : "layer " + std::to_string(c.obstacle_layer))
                << " near " << num(c.obstacle.x()) << "," << num(c.obstacle.y()) << ","
                << num(c.obstacle.z()) << ", depositing at " << num(c.nozzle_at.x()) << ","
                << num(c.nozzle_at.y()) << "," << num(c.nozzle_at.z());
        out << "\n# layer component origin normal min_thickness max_thickness area_mm2 "
               "volume_difference unsupported_mm2 paths\n";
        for (std::size_t i = 0; i < r.layers.size(); ++i) {
            const mas::Layer& l = r.layers[i];
            out << i << " " << l.component << " " << std::fixed << std::setprecision(4)
                << l.plane.origin.x() << "," << l.plane.origin.y() << "," << l.plane.origin.z()
                << " " << l.plane.normal.x() << "," << l.plane.normal.y() << ","
                << l.plane.normal.z() << " " << l.min_thickness_mm << " " << l.max_thickness_mm
                << " " << l.area_mm2 << " " << l.volume_difference << " " << l.unsupported_area_mm2
                << " " << r.toolpaths[i].paths.size() << "\n"
                << std::defaultfloat;
        }
    }
    write_output(a, out.str());
    return 0;
}

}  // namespace

int main(int argc, char** argv) {
    mas::silence_occt_console();  // standard output is the result; errors go to stderr ourselves
    std::vector<std::string> args(argv + 1, argv + argc);
    try {
        if (args.empty()) throw UsageError("no command given");
        const std::string command = args.front();
        args.erase(args.begin());
        if (command == "--help" || command == "-h") {
            std::cout << kUsage;
            return 0;
        }
        const bool known = command == "sections" || command == "axis" || command == "decompose" ||
                           command == "slice";
        if (known && std::find_if(args.begin(), args.end(), [](const std::string& a) {
                         return a == "--help" || a == "-h";
                     }) != args.end()) {
            std::cout << kUsage;  // `multiaxis-slicer axis --help`: the same text
            return 0;
        }
        if (command == "--version") {
            std::cout << "multiaxis-slicer 0.1.0\n";
            return 0;
        }
        if (command == "sections") return run_sections(args);
        if (command == "axis") return run_axis(args);
        if (command == "decompose") return run_decompose(args);
        if (command == "slice") return run_slice(args);
        throw UsageError("unknown command '" + command + "'");
    } catch (const UsageError& e) {
        std::cerr << "multiaxis-slicer: " << e.what() << " (see multiaxis-slicer --help)\n";
        return 2;
    } catch (const mas::Error& e) {
        std::cerr << "multiaxis-slicer: error (" << mas::to_string(e.code()) << "): " << e.what()
                  << "\n";
        return 1;
    } catch (const std::exception& e) {
        std::cerr << "multiaxis-slicer: internal error: " << e.what() << "\n";
        return 1;
    }
}
