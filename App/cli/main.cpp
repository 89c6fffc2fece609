// multiaxis-slicer: the engine on STEP / IGES / BREP / STL / OFF files, outside FreeCAD.
// Sub-commands grow with the pipeline; for now `sections` prints cross-section areas and centroids.
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <iomanip>
#include <iostream>
#include <sstream>
#include <string>
#include <vector>

#include "mas/Error.hpp"
#include "mas/Section.hpp"
#include "mas/Shape.hpp"

namespace {

const char* kUsage =
    "usage: multiaxis-slicer sections FILE [--normal X,Y,Z] [--step MM] [--deflection MM]\n"
    "                                      [--json [OUT.json]]\n"
    "       multiaxis-slicer --help | --version\n"
    "\n"
    "sections   cut the part with parallel planes STEP mm apart along NORMAL (default 0,0,1 and\n"
    "           1 mm), each in the middle of its slab, and print every section's area (mm^2),\n"
    "           region count and centroid; --json writes the same as JSON to OUT.json or stdout.\n"
    "FILE       .step/.stp, .iges/.igs, .brep/.brp (one closed solid) or .stl/.off (a closed "
    "mesh)\n"
    "--deflection MM  chordal deflection for tessellating a solid (default: derived from its "
    "size)\n";

struct UsageError : std::runtime_error {
    using std::runtime_error::runtime_error;
};

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

Eigen::Vector3d parse_vector(const std::string& text, const std::string& what) {
    std::vector<std::string> parts;
    std::stringstream in(text);
    for (std::string item; std::getline(in, item, ',');) parts.push_back(item);
    if (parts.size() != 3) throw UsageError(what + " must be X,Y,Z, got '" + text + "'");
    return {parse_number(parts[0], what), parse_number(parts[1], what),
            parse_number(parts[2], what)};
}

// Minimal JSON output: numbers with enough digits to round-trip the engine's doubles.
std::string num(double v) {
    std::ostringstream s;
    s << std::setprecision(15) << v;
    return s.str();
}

std::string vec(const Eigen::Vector3d& v) {
    return "[" + num(v.x()) + ", " + num(v.y()) + ", " + num(v.z()) + "]";
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

struct SectionsArgs {
    std::string file;
    Eigen::Vector3d normal{0, 0, 1};
    double step_mm = 1.0;
    double deflection_mm = 0.0;
    bool json = false;
    std::string json_path;  // empty: stdout
};

SectionsArgs parse_sections(const std::vector<std::string>& args) {
    SectionsArgs a;
    for (std::size_t i = 0; i < args.size(); ++i) {
        const std::string& arg = args[i];
        auto value = [&](const std::string& name) -> const std::string& {
            if (i + 1 >= args.size()) throw UsageError(name + " needs a value");
            return args[++i];
        };
        if (arg == "--normal")
            a.normal = parse_vector(value(arg), "--normal");
        else if (arg == "--step")
            a.step_mm = parse_number(value(arg), "--step");
        else if (arg == "--deflection")
            a.deflection_mm = parse_number(value(arg), "--deflection");
        else if (arg == "--json") {
            a.json = true;
            // FILE comes first; after it, a following non-option argument is the output path.
            if (!a.file.empty() && i + 1 < args.size() && args[i + 1].rfind("-", 0) != 0)
                a.json_path = args[++i];
        } else if (arg.rfind("--", 0) == 0)
            throw UsageError("unknown option " + arg);
        else if (a.file.empty())
            a.file = arg;
        else
            throw UsageError("unexpected argument '" + arg + "'");
    }
    if (a.file.empty()) throw UsageError("no input FILE given");
    if (!(a.step_mm > 0.0)) throw UsageError("--step must be positive, got " + num(a.step_mm));
    if (a.deflection_mm < 0.0)
        throw UsageError("--deflection must be positive (or 0 for automatic)");
    if (a.normal.norm() < 1e-12) throw UsageError("--normal must not be the zero vector");
    return a;
}

int run_sections(const std::vector<std::string>& args) {
    const SectionsArgs a = parse_sections(args);
    const mas::Model model = mas::read_model(a.file);
    mas::TessellationParams tp;
    tp.deflection_mm = a.deflection_mm;
    const double deflection =
        model.kind == mas::Model::Kind::Solid ? mas::effective_deflection(model.shape, tp) : 0.0;
    const mas::TriangleMesh mesh = mas::model_mesh(model, tp);
    const auto planes = mas::parallel_planes(mesh, a.normal, a.step_mm);
    const auto sections = mas::slice_mesh(mesh, planes);
    const Eigen::Vector3d n = planes.front().normal;

    std::ostringstream out;
    if (a.json) {
        out << "{\n  \"file\": " << quoted(a.file)
            << ",\n  \"kind\": " << quoted(model.kind == mas::Model::Kind::Solid ? "solid" : "mesh")
            << ",\n  \"triangles\": " << mesh.triangles.size()
            << ",\n  \"deflection_mm\": " << num(deflection) << ",\n  \"normal\": " << vec(n)
            << ",\n  \"step_mm\": " << num(a.step_mm) << ",\n  \"sections\": [";
        for (std::size_t i = 0; i < sections.size(); ++i) {
            const auto& s = sections[i];
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
        }
        out << "\n  ]\n}\n";
    } else {
        out << "# " << a.file << ": " << (model.kind == mas::Model::Kind::Solid ? "solid" : "mesh")
            << ", " << mesh.triangles.size() << " triangles";
        if (deflection > 0.0) out << ", deflection " << num(deflection) << " mm";
        out << "\n# normal " << num(n.x()) << "," << num(n.y()) << "," << num(n.z()) << ", step "
            << num(a.step_mm) << " mm, " << sections.size() << " sections\n";
        out << "# offset_mm regions holes area_mm2 centroid_x centroid_y centroid_z\n";
        for (const auto& s : sections) {
            std::size_t holes = 0;
            for (const auto& r : s.regions) holes += r.shape.holes.size();
            out << std::fixed << std::setprecision(4) << n.dot(s.plane.origin) << " "
                << s.regions.size() << " " << holes << " " << s.area << " " << s.centroid.x() << " "
                << s.centroid.y() << " " << s.centroid.z() << "\n";
        }
    }
    if (a.json && !a.json_path.empty()) {
        std::ofstream file(a.json_path);
        if (!(file << out.str()))
            throw mas::Error(mas::ErrorCode::ReadFailed, a.json_path + ": cannot write the file");
    } else {
        std::cout << out.str();
    }
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
        if (command == "--version") {
            std::cout << "multiaxis-slicer 0.1.0\n";
            return 0;
        }
        if (command == "sections") return run_sections(args);
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
