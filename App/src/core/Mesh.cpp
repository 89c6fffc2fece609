// Triangle mesh checks, welding and the OFF reader.
#include "mas/Mesh.hpp"

#include <algorithm>
#include <array>
#include <cctype>
#include <cerrno>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <fstream>
#include <limits>
#include <numeric>
#include <optional>
#include <sstream>
#include <tuple>
#include <unordered_map>

#include "mas/Angles.hpp"
#include "mas/Error.hpp"

namespace mas {

namespace {

bool finite(const Eigen::Vector3d& p) { return p.allFinite(); }

// Triangle t's share of the mesh's volume: the signed volume of the tetrahedron it makes with
// `apex` (volume_apex(mesh)).
double volume_share(const TriangleMesh& mesh, const Eigen::Vector3i& t,
                    const Eigen::Vector3d& apex) {
    return tetra_volume(mesh.vertices[std::size_t(t[0])] - apex,
                        mesh.vertices[std::size_t(t[1])] - apex,
                        mesh.vertices[std::size_t(t[2])] - apex);
}

// Generalised winding number of `point` about the triangles `tris` of `mesh`: the sum of their
// signed solid angles over 4 pi (Van Oosterom & Strackee). +1 inside an outward shell, -1 inside
// an inward one, 0 outside, +-1/2 on it.
double winding(const TriangleMesh& mesh, const std::vector<std::size_t>& tris,
               const Eigen::Vector3d& point) {
    double total = 0.0;
    for (const std::size_t i : tris) {
        const Eigen::Vector3i& t = mesh.triangles[i];
        const Eigen::Vector3d a = mesh.vertices[std::size_t(t[0])] - point;
        const Eigen::Vector3d b = mesh.vertices[std::size_t(t[1])] - point;
        const Eigen::Vector3d c = mesh.vertices[std::size_t(t[2])] - point;
        const double la = a.norm(), lb = b.norm(), lc = c.norm();
        total += 2.0 * std::atan2(a.dot(b.cross(c)),
                                  la * lb * lc + a.dot(b) * lc + b.dot(c) * la + c.dot(a) * lb);
    }
    return total / (4.0 * kPi);
}

}  // namespace

// A closed, consistently oriented mesh of several shells (connected by their vertices) is a solid
// only if each shell bounds material on its inner side: an outer shell faces out, a cavity's
// shell, inside one outer shell, faces in, an island in a cavity out again. So a shell nested in
// the others to winding number k must face out for k = 0 and in for k = 1; any other k (shells
// overlapping, or one inside another of the same orientation) is no solid. The centroids of up to
// 32 of each shell's triangles, and a point just inside each by its first corner, are tested
// against the shells whose box holds them (a point lying on another shell tells nothing and is
// skipped), fewer when the shells are large and nested: at most about 4e7 solid angles in all
// (two seconds), and at least two points per shell. Shells that cross with no tested point inside
// each other (two bars crossing like a plus sign) pass unseen.
// Throws NotASolid naming the first fault.
void require_one_solid(const TriangleMesh& mesh, const std::string& what) {
    const std::size_t nv = mesh.vertices.size();
    std::vector<std::size_t> root(nv);
    for (std::size_t i = 0; i < nv; ++i) root[i] = i;
    const auto find = [&](std::size_t i) {
        while (root[i] != i) i = root[i] = root[root[i]];
        return i;
    };
    for (const auto& t : mesh.triangles)
        for (int k = 1; k < 3; ++k) {
            const std::size_t a = find(std::size_t(t[0])), b = find(std::size_t(t[k]));
            if (a != b) root[std::max(a, b)] = std::min(a, b);
        }
    std::unordered_map<std::size_t, std::size_t> shell_of;  // root vertex -> shell index
    std::vector<std::vector<std::size_t>> tris;
    for (std::size_t i = 0; i < mesh.triangles.size(); ++i) {
        const std::size_t r = find(std::size_t(mesh.triangles[i][0]));
        const auto [it, added] = shell_of.emplace(r, tris.size());
        if (added) tris.emplace_back();
        tris[it->second].push_back(i);
    }
    if (tris.size() < 2) return;
    std::vector<double> volume(tris.size(), 0.0);
    const Eigen::Vector3d apex = volume_apex(mesh);
    std::vector<Eigen::AlignedBox3d> box(tris.size());
    for (std::size_t s = 0; s < tris.size(); ++s) {
        for (const std::size_t i : tris[s]) {
            const Eigen::Vector3i& t = mesh.triangles[i];
            const Eigen::Vector3d &p0 = mesh.vertices[std::size_t(t[0])],
                                  &p1 = mesh.vertices[std::size_t(t[1])],
                                  &p2 = mesh.vertices[std::size_t(t[2])];
            volume[s] += volume_share(mesh, t, apex);
            box[s].extend(p0);
            box[s].extend(p1);
            box[s].extend(p2);
        }
    }
    // The shells each shell's points may lie in (their boxes meet), and the solid angles one point
    // of each shell costs, over all shells: the budget's share.
    std::vector<std::vector<std::size_t>> near(tris.size());
    double per_point = 0.0;
    for (std::size_t s = 0; s < tris.size(); ++s)
        for (std::size_t o = 0; o < tris.size(); ++o)
            if (o != s && box[o].intersects(box[s])) {
                near[s].push_back(o);
                per_point += double(tris[o].size());
            }
    const std::size_t points =
        per_point > 0.0 ? std::size_t(std::clamp(std::floor(2e7 / per_point), 1.0, 32.0)) : 1;
    for (std::size_t s = 0; s < tris.size(); ++s) {
        // Facet centres, and points by the shell's corners: two cubes overlapping at a corner
        // have no facet centre inside each other, but each has a corner inside the other. The
        // point lies just inside the facet, off the corner itself, which may sit exactly on
        // another shell's vertex (an island touching its cavity's corner), where the winding
        // number is a fraction that tells nothing.
        std::vector<Eigen::Vector3d> samples;
        const std::size_t stride = std::max<std::size_t>(1, tris[s].size() / points);
        for (std::size_t j = 0; j < tris[s].size(); j += stride) {
            const Eigen::Vector3i& t = mesh.triangles[tris[s][j]];
            const Eigen::Vector3d centre =
                (mesh.vertices[std::size_t(t[0])] + mesh.vertices[std::size_t(t[1])] +
                 mesh.vertices[std::size_t(t[2])]) /
                3.0;
            samples.push_back(centre);
            samples.push_back(0.98 * mesh.vertices[std::size_t(t[0])] + 0.02 * centre);
        }
        for (const Eigen::Vector3d& p : samples) {
            double depth = 0.0;
            bool on_another = false;
            for (const std::size_t o : near[s]) {
                if (!box[o].contains(p)) continue;
                const double w = winding(mesh, tris[o], p);
                if (std::abs(w - std::round(w)) > 0.25) {
                    on_another = true;
                    break;
                }
                depth += std::round(w);
            }
            if (on_another) continue;
            const bool outward = volume[s] > 0.0;
            if ((depth == 0.0 && outward) || (depth == 1.0 && !outward)) continue;
            std::ostringstream msg;
            msg << what << ": the mesh is not one solid: of its " << tris.size()
                << " shells, shell " << s + 1 << " (" << tris[s].size() << " triangles, facing "
                << (outward ? "out" : "in") << ") ";
            if (depth == 0.0)
                msg << "lies outside the others but faces in (inside out)";
            else if (depth == 1.0)
                msg << "lies inside another but faces out (overlapping shells, or a cavity's "
                       "shell facing the wrong way)";
            else if (depth > 1.0)
                msg << "lies inside " << depth << " others at once (overlapping shells)";
            else
                msg << "lies inside shells facing in that no shell facing out holds";
            throw Error(ErrorCode::NotASolid, msg.str());
        }
    }
}

double mesh_volume(const TriangleMesh& mesh) {
    double volume = 0.0;
    const Eigen::Vector3d apex = volume_apex(mesh);
    for (const Eigen::Vector3i& t : mesh.triangles) volume += volume_share(mesh, t, apex);
    return volume;
}

MeshReport check_mesh(const TriangleMesh& mesh) {
    MeshReport r;
    r.vertices = mesh.vertices.size();
    r.triangles = mesh.triangles.size();
    for (const auto& v : mesh.vertices)
        if (!finite(v)) ++r.non_finite_vertices;

    // Every undirected edge with the directions it is used in: +1 for (lo, hi), -1 for (hi, lo).
    struct EdgeUse {
        std::uint64_t key;
        int direction;
    };
    std::vector<EdgeUse> uses;
    uses.reserve(mesh.triangles.size() * 3);
    const auto n = static_cast<int>(mesh.vertices.size());
    const Eigen::Vector3d apex = volume_apex(mesh);
    for (const auto& t : mesh.triangles) {
        if (t[0] == t[1] || t[1] == t[2] || t[2] == t[0]) {
            ++r.degenerate_triangles;
            continue;
        }
        if (t.minCoeff() < 0 || t.maxCoeff() >= n) {
            ++r.degenerate_triangles;
            continue;
        }
        for (int k = 0; k < 3; ++k) {
            const auto a = static_cast<std::uint32_t>(t[k]);
            const auto b = static_cast<std::uint32_t>(t[(k + 1) % 3]);
            const auto lo = std::min(a, b), hi = std::max(a, b);
            uses.push_back({(std::uint64_t(lo) << 32) | hi, a < b ? 1 : -1});
        }
        r.volume_mm3 += volume_share(mesh, t, apex);
    }
    std::sort(uses.begin(), uses.end(),
              [](const EdgeUse& x, const EdgeUse& y) { return x.key < y.key; });
    for (std::size_t i = 0; i < uses.size();) {
        std::size_t j = i;
        int sum = 0;
        while (j < uses.size() && uses[j].key == uses[i].key) sum += uses[j++].direction;
        const std::size_t count = j - i;
        if (count == 1)
            ++r.boundary_edges;
        else if (count > 2)
            ++r.non_manifold_edges;
        else if (sum != 0)
            ++r.inconsistent_edges;
        i = j;
    }
    return r;
}

void require_closed_mesh(TriangleMesh& mesh, const std::string& what) {
    if (mesh.triangles.empty() || mesh.vertices.empty())
        throw Error(ErrorCode::EmptyInput, what + ": the mesh has no triangles");
    const MeshReport r = check_mesh(mesh);
    if (r.non_finite_vertices > 0)
        throw Error(ErrorCode::NonFiniteCoordinate,
                    what + ": " + std::to_string(r.non_finite_vertices) +
                        " vertices have NaN or infinite coordinates");
    double farthest = 0.0;
    for (const Eigen::Vector3d& v : mesh.vertices)
        farthest = std::max(farthest, v.cwiseAbs().maxCoeff());
    if (farthest > kMaxCoordinateMm)
        throw Error(ErrorCode::NonFiniteCoordinate,
                    what + ": a vertex lies " + format_number(farthest) +
                        " mm from the origin along an axis, beyond the " +
                        format_number(kMaxCoordinateMm) + " mm (1000 km) the engine works within");
    if (!r.closed()) {
        std::ostringstream msg;
        msg << what << ": the mesh is not a closed solid (" << r.boundary_edges
            << " boundary edges, " << r.non_manifold_edges << " non-manifold edges, "
            << r.inconsistent_edges << " edges with inconsistent orientation)";
        throw Error(ErrorCode::OpenMesh, msg.str());
    }
    if (r.degenerate_triangles == r.triangles)
        throw Error(ErrorCode::EmptyInput, what + ": every triangle of the mesh is degenerate");
    // A closed surface folded flat (a square's top lying on its bottom) holds no material: its
    // sections are empty and its axis has no height.
    const double size = bounding_box(mesh).diagonal().norm();
    if (!(std::abs(r.volume_mm3) > 1e-12 * size * size * size))
        throw Error(ErrorCode::EmptyInput, what + ": the mesh encloses no volume (" +
                                               format_number(r.volume_mm3) + " mm^3 within a box " +
                                               format_number(size) + " mm across)");
    if (r.volume_mm3 < 0.0)  // closed and consistent, but inside out
        for (auto& t : mesh.triangles) std::swap(t[1], t[2]);
}

void canonical_order(TriangleMesh& mesh) {
    const std::size_t nv = mesh.vertices.size();
    std::vector<int> by_position(nv);
    std::iota(by_position.begin(), by_position.end(), 0);
    const auto less = [&](int a, int b) {
        const Eigen::Vector3d& p = mesh.vertices[std::size_t(a)];
        const Eigen::Vector3d& q = mesh.vertices[std::size_t(b)];
        return std::tie(p.x(), p.y(), p.z()) < std::tie(q.x(), q.y(), q.z());
    };
    std::stable_sort(by_position.begin(), by_position.end(), less);
    std::vector<int> new_index(nv);
    std::vector<Eigen::Vector3d> vertices(nv);
    for (std::size_t k = 0; k < nv; ++k) {
        new_index[std::size_t(by_position[k])] = int(k);
        vertices[k] = mesh.vertices[std::size_t(by_position[k])];
    }
    mesh.vertices = std::move(vertices);
    for (Eigen::Vector3i& t : mesh.triangles) {
        for (int k = 0; k < 3; ++k) t[k] = new_index[std::size_t(t[k])];
        // Start at the least index, the turn (the facet's orientation) kept.
        while (t[0] > t[1] || t[0] > t[2]) t = Eigen::Vector3i(t[1], t[2], t[0]);
    }
    std::sort(mesh.triangles.begin(), mesh.triangles.end(),
              [](const Eigen::Vector3i& a, const Eigen::Vector3i& b) {
                  return std::tie(a[0], a[1], a[2]) < std::tie(b[0], b[1], b[2]);
              });
}

std::size_t weld_vertices(TriangleMesh& mesh, double tolerance_mm) {
    if (!(tolerance_mm > 0.0) || !std::isfinite(tolerance_mm))
        throw Error(ErrorCode::InvalidArgument, "weld tolerance must be positive");
    struct CellHash {
        std::size_t operator()(const std::array<std::int64_t, 3>& c) const {
            return std::size_t(c[0] * 73856093LL ^ c[1] * 19349663LL ^ c[2] * 83492791LL);
        }
    };
    std::unordered_map<std::array<std::int64_t, 3>, std::vector<int>, CellHash> grid;
    grid.reserve(mesh.vertices.size());
    std::vector<int> remap(mesh.vertices.size());
    std::vector<Eigen::Vector3d> kept;
    kept.reserve(mesh.vertices.size());
    const double tol2 = tolerance_mm * tolerance_mm;
    for (std::size_t i = 0; i < mesh.vertices.size(); ++i) {
        const Eigen::Vector3d& p = mesh.vertices[i];
        const std::array<std::int64_t, 3> c{std::int64_t(std::floor(p.x() / tolerance_mm)),
                                            std::int64_t(std::floor(p.y() / tolerance_mm)),
                                            std::int64_t(std::floor(p.z() / tolerance_mm))};
        int found = -1;
        for (int dx = -1; dx <= 1 && found < 0; ++dx)
            for (int dy = -1; dy <= 1 && found < 0; ++dy)
                for (int dz = -1; dz <= 1 && found < 0; ++dz) {
                    auto it = grid.find({c[0] + dx, c[1] + dy, c[2] + dz});
                    if (it == grid.end()) continue;
                    for (int k : it->second)
                        if ((kept[k] - p).squaredNorm() <= tol2) {
                            found = k;
                            break;
                        }
                }
        if (found < 0) {
            found = static_cast<int>(kept.size());
            kept.push_back(p);
            grid[c].push_back(found);
        }
        remap[i] = found;
    }
    const std::size_t removed = mesh.vertices.size() - kept.size();
    std::vector<Eigen::Vector3i> tris;
    tris.reserve(mesh.triangles.size());
    for (const auto& t : mesh.triangles) {
        const Eigen::Vector3i m(remap[t[0]], remap[t[1]], remap[t[2]]);
        if (m[0] != m[1] && m[1] != m[2] && m[2] != m[0]) tris.push_back(m);
    }
    mesh.vertices = std::move(kept);
    mesh.triangles = std::move(tris);
    return removed;
}

Eigen::AlignedBox3d bounding_box(const TriangleMesh& mesh) {
    Eigen::AlignedBox3d box;
    for (const auto& t : mesh.triangles)
        for (int k = 0; k < 3; ++k) box.extend(mesh.vertices[t[k]]);
    return box;
}

void range_along(const Eigen::AlignedBox3d& box, const Eigen::Vector3d& direction, double& lo,
                 double& hi) {
    lo = std::numeric_limits<double>::infinity();
    hi = -lo;
    for (int i = 0; i < 8; ++i) {
        const double t = direction.dot(box.corner(static_cast<Eigen::AlignedBox3d::CornerType>(i)));
        lo = std::min(lo, t);
        hi = std::max(hi, t);
    }
}

namespace {

// An OFF file's text, comments (#...) removed, read number by number.
class OffText {
public:
    OffText(std::istream& in, const std::string& path) : path_(path) {
        for (std::string line; std::getline(in, line);) {
            const auto hash = line.find('#');
            if (hash != std::string::npos) line.erase(hash);
            text_ += line;
            text_ += '\n';
        }
    }

    // The next whitespace-separated token; false at the end.
    bool next(std::string& token) {
        while (pos_ < text_.size() && std::isspace(static_cast<unsigned char>(text_[pos_]))) ++pos_;
        if (pos_ == text_.size()) return false;
        const std::size_t start = pos_;
        while (pos_ < text_.size() && !std::isspace(static_cast<unsigned char>(text_[pos_])))
            ++pos_;
        token.assign(text_, start, pos_ - start);
        return true;
    }

    // Past the end of the current line (what a face line carries after its indices: colours).
    void skip_line() {
        pos_ = text_.find('\n', pos_);
        if (pos_ == std::string::npos) pos_ = text_.size();
    }

    // At most how many more tokens the text holds: each takes a character and a separator. What
    // a count announced beyond that is a truncated (or garbled) file; checked before reserving
    // room for it, so that a few bytes cannot ask for gigabytes.
    long long tokens_left() const { return static_cast<long long>(text_.size() - pos_ + 1) / 2; }

    // A whole integer token (none of "1.5", "1x"), or nullopt.
    std::optional<long long> integer() {
        last_.clear();
        std::string token;
        if (!next(token)) return std::nullopt;
        last_ = token;
        errno = 0;
        char* end = nullptr;
        const long long value = std::strtoll(token.c_str(), &end, 10);
        if (errno == ERANGE || end != token.c_str() + token.size()) return std::nullopt;
        return value;
    }

    // A whole coordinate token; "nan" and "inf" parse (require_closed_mesh names them later).
    double coordinate() {
        std::string token;
        if (!next(token))
            throw Error(ErrorCode::ReadFailed, path_ + ": truncated OFF file (vertices)");
        errno = 0;
        char* end = nullptr;
        const double value = std::strtod(token.c_str(), &end);
        if (end != token.c_str() + token.size())
            throw Error(ErrorCode::ReadFailed, path_ + ": bad vertex coordinate '" + token + "'");
        // Past a double's range (1e400) is an error; below it (1e-400) a coordinate next to 0.
        if (errno == ERANGE && std::isinf(value))
            throw Error(ErrorCode::NonFiniteCoordinate, path_ + ": vertex coordinate '" + token +
                                                            "' is beyond the range of a number");
        return value;
    }

    // The token integer() last read ("" at the end of the text).
    const std::string& last() const { return last_; }

private:
    std::string path_, text_, last_;
    std::size_t pos_ = 0;
};

}  // namespace

TriangleMesh read_off(const std::string& path) {
    std::ifstream in(path);
    if (!in) throw Error(ErrorCode::ReadFailed, path + ": cannot open the file");
    OffText text(in, path);
    std::string header;
    if (!text.next(header)) throw Error(ErrorCode::EmptyInput, path + ": the file is empty");
    // Geomview's [ST][C][N]OFF: texture coordinates, colours and normals follow each vertex's
    // three coordinates on its line (CGAL's and MeshLab's COFF, with colours); the 4-D and n-D
    // variants ([4][n]OFF) and binary OFF are not read.
    const bool ends_off = header.size() >= 3 && header.compare(header.size() - 3, 3, "OFF") == 0;
    std::string prefix = ends_off ? header.substr(0, header.size() - 3) : header;
    const bool more_per_vertex = ends_off && !prefix.empty();
    if (prefix.compare(0, 2, "ST") == 0) prefix.erase(0, 2);
    if (!prefix.empty() && prefix.front() == 'C') prefix.erase(0, 1);
    if (!prefix.empty() && prefix.front() == 'N') prefix.erase(0, 1);
    if (!ends_off || !prefix.empty()) {
        const bool dimension = ends_off && (prefix == "4" || prefix == "n" || prefix == "4n");
        throw Error(ErrorCode::ReadFailed,
                    path + ": not an OFF file (header '" + header + "'" +
                        (dimension ? ": vertices of other than three coordinates)" : ")"));
    }
    const auto nv = text.integer();
    if (!nv && text.last() == "BINARY")
        throw Error(ErrorCode::ReadFailed,
                    path + ": a binary OFF file: only OFF as text is read (save it as ASCII)");
    const auto nf = text.integer(), ne = text.integer();
    if (!nv || !nf || !ne || *nv < 0 || *nf < 0)
        throw Error(ErrorCode::ReadFailed, path + ": bad OFF counts line");
    const auto truncated = [&](const std::string& what) {
        return Error(ErrorCode::ReadFailed, path + ": truncated OFF file: " + what);
    };
    if (*nv > text.tokens_left() / 3)
        throw truncated("it announces " + std::to_string(*nv) + " vertices and holds at most " +
                        std::to_string(text.tokens_left() / 3));
    if (*nv > std::numeric_limits<int>::max())
        throw Error(ErrorCode::ReadFailed, path + ": " + std::to_string(*nv) +
                                               " vertices, more than a mesh here can index");
    TriangleMesh mesh;
    mesh.vertices.reserve(static_cast<std::size_t>(*nv));
    for (long long i = 0; i < *nv; ++i) {
        const double x = text.coordinate(), y = text.coordinate(), z = text.coordinate();
        if (more_per_vertex) text.skip_line();
        mesh.vertices.emplace_back(x, y, z);
        if (!mesh.vertices.back().allFinite())
            throw Error(ErrorCode::NonFiniteCoordinate,
                        path + ": a vertex has NaN or infinite coordinates");
    }
    if (*nf > text.tokens_left() / 4)
        throw truncated("it announces " + std::to_string(*nf) + " faces and holds at most " +
                        std::to_string(text.tokens_left() / 4));
    mesh.triangles.reserve(static_cast<std::size_t>(*nf));
    std::vector<int> idx;
    for (long long f = 0; f < *nf; ++f) {
        const auto k = text.integer();
        if (!k && text.last().empty())
            throw Error(ErrorCode::ReadFailed, path + ": truncated OFF file (faces)");
        if (!k || *k < 3)
            throw Error(ErrorCode::ReadFailed,
                        path + ": bad corner count '" + text.last() + "' in a face (3 or more)");
        if (*k > text.tokens_left())
            throw truncated("a face announces " + std::to_string(*k) +
                            " corners and the file holds at most " +
                            std::to_string(text.tokens_left()) + " more numbers");
        idx.clear();
        for (long long c = 0; c < *k; ++c) {
            const auto i = text.integer();
            if (!i) {
                if (text.last().empty())
                    throw Error(ErrorCode::ReadFailed, path + ": truncated OFF file (faces)");
                throw Error(ErrorCode::ReadFailed,
                            path + ": bad vertex index '" + text.last() + "' in a face");
            }
            if (*i < 0 || *i >= *nv)
                throw Error(ErrorCode::ReadFailed, path + ": bad vertex index '" + text.last() +
                                                       "' in a face (" + std::to_string(*nv) +
                                                       " vertices)");
            idx.push_back(static_cast<int>(*i));
        }
        text.skip_line();  // per-face colours may follow on the same line
        for (std::size_t j = 1; j + 1 < idx.size(); ++j)
            mesh.triangles.emplace_back(idx[0], idx[j], idx[j + 1]);
    }
    if (mesh.triangles.empty()) throw Error(ErrorCode::EmptyInput, path + ": no faces");
    return mesh;
}

void write_stl(const TriangleMesh& mesh, const std::string& path) {
    std::ofstream out(path, std::ios::binary);
    if (!out) throw Error(ErrorCode::WriteFailed, path + ": cannot be written");
    char header[80] = "Multi-Axis Slicer mesh";
    out.write(header, sizeof header);
    const std::uint32_t count = std::uint32_t(mesh.triangles.size());
    out.write(reinterpret_cast<const char*>(&count), 4);
    for (const Eigen::Vector3i& t : mesh.triangles) {
        float record[12] = {0.0f, 0.0f, 0.0f};
        for (int k = 0; k < 3; ++k)
            for (int c = 0; c < 3; ++c)
                record[3 + 3 * k + c] = float(mesh.vertices[std::size_t(t[k])][c]);
        out.write(reinterpret_cast<const char*>(record), sizeof record);
        const std::uint16_t attributes = 0;
        out.write(reinterpret_cast<const char*>(&attributes), 2);
    }
    if (!out.flush()) throw Error(ErrorCode::WriteFailed, path + ": cannot be written");
}

}  // namespace mas
